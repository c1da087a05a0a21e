#pragma once
// Plots of logged signals, drawn by gnuplot.
//
// We write a gnuplot script beside the plot (so a user can restyle and re-run
// it) and run gnuplot on it without a shell: one panel per logged group, time
// on the x axis. PNG (pngcairo) or SVG, chosen by the file's extension.

#include <string>
#include <vector>

#include "blocks/results.h"
#include "diagrams/loader.h"

namespace mechflow::cli {

// The gnuplot script that draws `groups` of the CSV file `csv_path` into
// `plot_path` (absolute paths are best: gnuplot runs in another folder).
std::string GnuplotScript(const blocks::Results& results, const std::vector<diagrams::PlotGroup>& groups,
                          const std::string& title, const std::string& csv_path, const std::string& plot_path);

// Writes `plot_path + ".gp"` and runs gnuplot on it. Returns "" on success,
// otherwise why no plot was made (gnuplot missing, gnuplot failed).
std::string DrawPlot(const std::string& script, const std::string& plot_path);

}  // namespace mechflow::cli
