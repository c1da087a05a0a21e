#pragma once
// Plots of logged signals, drawn by gnuplot.
//
// We write a gnuplot script beside the plot (so a user can restyle and re-run
// it) and run gnuplot on it without a shell: one panel per logged group, time
// on the x axis. PNG (pngcairo) or SVG, chosen by the file's extension.

#include <string>
#include <vector>

#include "blocks/outputs/results.h"
#include "cli/output_folder.h"
#include "cli/plot_envelope.h"
#include "diagrams/loader.h"

namespace mechflow::cli {

// A long run's plot data (cli/plot_envelope.h), written beside the plot:
// the time panels draw from `name`, the x-y panels from `xy_name`.
struct EnvelopeFiles {
  const PlotEnvelope* envelope = nullptr;  // nullptr: every row of the CSV
  std::string name, xy_name;
};

// The gnuplot script that draws `groups` of the CSV file `csv_name` into
// `plot_name`, both plain names in the folder gnuplot runs in. Every text
// is a single-quoted gnuplot string that cannot end its line.
// `xy`: panels of one column against another, after the time panels.
// With an envelope, the time panels draw its band between each column's
// min and max lines, in the colours they would have.
std::string GnuplotScript(const blocks::Results& results, const std::vector<diagrams::PlotGroup>& groups,
                          const std::string& title, const std::string& csv_name, const std::string& plot_name,
                          const std::vector<diagrams::XYPlotRequest>& xy = {}, const EnvelopeFiles& envelope = {});

// One run of a sweep for the overlay: its results file and its label
// ("beta=0.1").
struct OverlayRun {
  std::string csv_name, label;
  // a long run: its envelope of PlottedColumns(groups), drawn instead
  std::string envelope_name = {};
};
// Numbers as a legend shows them, one text per value: 6 significant digits
// ("0.0316228", not 0.0316227766016838), more where fewer would show two
// different values alike (1 and 1.0000001), so every run is told apart.
// A negative zero is 0.
std::vector<std::string> LegendNumbers(const std::vector<double>& values);

// The sweep's overlay (the seed's Fig. 7.2): a panel per logged group, in it
// every column of the group from every run, labelled by the run; each
// curve of a panel in a look of its own (colour, then dash type).
std::string OverlayScript(const std::vector<diagrams::PlotGroup>& groups, const std::vector<std::string>& columns,
                          const std::vector<OverlayRun>& runs, const std::string& title, const std::string& plot_name);

// Writes `plot_name + ".gp"` into the folder and runs gnuplot on it there
// (standard input /dev/null, the script passed as "./NAME.gp").
// Returns "" when the plot was drawn, or why gnuplot could not be run (not
// installed), a warning. Throws WriteError when gnuplot failed or made no
// plot file, or one without its end (a PNG without IEND, an SVG without
// </svg>: cut by a full disk; removed). A signal to mechflow while gnuplot
// draws stops gnuplot and throws Interrupted (cli/interrupt.h); from then
// on no plot is started.
std::string DrawPlot(const std::string& script, const OutputFolder& folder, const std::string& plot_name);

}  // namespace mechflow::cli
