#pragma once
// The files of one `mechflow run`, written into its output folder: the
// results CSV (streamed during the run: cli/results_file.h), the figures of its <report>s (NAME.report.csv), the control
// script's changes (NAME.changes.csv) and the plot with its gnuplot script.

#include <cstdint>
#include <memory>
#include <ostream>

#include "blocks/solver/simulator.h"
#include "cli/output_folder.h"
#include "cli/plot_envelope.h"
#include "cli/results_file.h"
#include "diagrams/loader.h"
#include "run/columns.h"

namespace mechflow::cli {

// The run's results file, made before the run (its rows go to `envelope`,
// the plot's, when not nullptr, which passes them on to the file). The file
// stops at `max_bytes` (ResultsFile::stopped). Throws InputError when it
// cannot be made.
std::unique_ptr<ResultsFile> OpenResults(const diagrams::LoadedDiagram& loaded, const blocks::Simulator& sim,
                                         const OutputFolder& folder, std::uint64_t max_bytes, PlotEnvelope* envelope);

// Closes the results file and writes every other file the run has
// something for, saying each one on `out`.
// A file that cannot be written is reported on `err`, the others are still
// written, and the end lists what was written, cut (the results CSV, kept
// with its rows before the cut) and not written; returns false then (exit
// code 1). A signal while gnuplot draws stops the plots (the other files are
// still written) and sets `*stopped_by` to it.
// A long run's plot is drawn from `envelope` (written beside it) when given.
// `columns` are the run's (run::PreparedRun::columns), named with their units.
bool WriteRunOutputs(const diagrams::LoadedDiagram& loaded, const blocks::Simulator& sim,
                     const std::vector<run::Column>& columns, const OutputFolder& folder, ResultsFile* results_file, std::ostream& out, std::ostream& err, int* stopped_by,
                     const PlotEnvelope* envelope = nullptr);

}  // namespace mechflow::cli
