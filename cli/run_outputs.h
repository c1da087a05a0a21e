#pragma once
// The files of one `mechflow run`, written into its output folder: the
// results CSV, the figures of its <report>s (NAME.report.csv), the control
// script's changes (NAME.changes.csv) and the plot with its gnuplot script.

#include <ostream>

#include "blocks/simulator.h"
#include "cli/output_folder.h"
#include "diagrams/loader.h"

namespace mechflow::cli {

// Writes every file the run has something for, saying each one on `out`.
// A file that cannot be written is reported on `err`, the others are still
// written, and the end says what was and was not written; returns false
// then (exit code 1).
bool WriteRunOutputs(const diagrams::LoadedDiagram& loaded, const blocks::Simulator& sim, const OutputFolder& folder,
                     std::ostream& out, std::ostream& err);

}  // namespace mechflow::cli
