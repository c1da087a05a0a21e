#pragma once
// The files of one `mechflow run`, written into its output folder: the
// results CSV (streamed during the run: cli/results_file.h), the figures of its <report>s (NAME.report.csv), the control
// script's changes (NAME.changes.csv) and the plot with its gnuplot script.
// With --results - the results go to standard output instead, and the other
// files into --out, or nowhere without it.

#include <cstdint>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "blocks/solver/simulator.h"
#include "cli/output_claims.h"
#include "cli/output_folder.h"
#include "cli/plot_envelope.h"
#include "cli/results_file.h"
#include "diagrams/loader.h"
#include "run/columns.h"

namespace mechflow::cli {

// Where a run's files go.
struct RunOutputPlan {
  // the folder of every file; nullptr: none but the results, which then go
  // to standard output (--results - without --out)
  const OutputFolder* folder = nullptr;
  // >= 0: the results CSV goes to this descriptor of standard output
  // (--results -: cli/results_file.h), owned by the results file from then on
  int results_fd = -1;
  bool plot = true;  // the plot and the <spectrum>s' plots (not with --no-plot or --results -)
};

// The run's results file, made before the run (its rows go to `envelope`,
// the plot's, when not nullptr, which passes them on to the file). The file
// stops at `max_bytes` (ResultsFile::stopped). Throws InputError when it
// cannot be made.
std::unique_ptr<ResultsFile> OpenResults(const diagrams::LoadedDiagram& loaded, const blocks::Simulator& sim,
                                         const RunOutputPlan& plan, std::uint64_t max_bytes, PlotEnvelope* envelope);

// Where the results' name comes from, for messages: "--results d.csv",
// "<output csv=\"d.csv\">" or "the diagram's name \"d\"".
std::string ResultsNameOrigin(const diagrams::LoadedDiagram& loaded, const std::optional<std::string>& results_option);

// The stems of the files the run writes into its folder (cli/output_claims.h):
// the results' (everything beside them is named after it) and the plot's,
// each with where its name comes from; `results_option` is --results.
std::vector<OutputStem> RunStems(const diagrams::LoadedDiagram& loaded, const RunOutputPlan& plan,
                                 const std::optional<std::string>& results_option);

// With --results -, says on `out` (before the run) what the diagram asks
// for that is not written: every file without --out, the plots in any case
// (unless --no-plot, `no_plot`, already says so).
void SayWhatStandardOutputLeavesOut(const diagrams::LoadedDiagram& loaded, const RunOutputPlan& plan, bool no_plot,
                                    std::ostream& out);

// Closes the results file and writes every other file the run has
// something for, saying each one on `out`.
// A file that cannot be written is reported on `err`, the others are still
// written, and the end lists what was written, cut (the results CSV, kept
// with its rows before the cut) and not written; returns false then (exit
// code 1). A signal while gnuplot draws stops the plots (the other files are
// still written) and sets `*stopped_by` to it.
// A long run's plot is drawn from `envelope` (written beside it) when given.
// `columns` are the run's (run::PreparedRun::columns), named with their units.
// With no folder in `plan`, only the results file is closed.
bool WriteRunOutputs(const diagrams::LoadedDiagram& loaded, const blocks::Simulator& sim,
                     const std::vector<run::Column>& columns, const RunOutputPlan& plan, ResultsFile* results_file,
                     std::ostream& out, std::ostream& err, int* stopped_by, const PlotEnvelope* envelope = nullptr);

}  // namespace mechflow::cli
