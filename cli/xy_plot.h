#pragma once
// X-y plots drawn by gnuplot (cli/plot.h draws time histories): panels of
// curves, each a column of a CSV file against another, with axis labels and
// optional log scales. Force-analysis loops, dynamic stiffness against a
// parameter, spectra.
//
// Every row of the CSV is drawn: these files do not grow with a run's
// length (a loop has --samples rows of one period, a spectrum half a
// --segment, a stiffness table a row per case). A run's own <xy> panels,
// which do, are drawn by cli/plot.h from the extreme rows of each bin of
// time (cli/plot_envelope.h).

#include <string>
#include <vector>

namespace mechflow::cli {

struct XYCurve {
  int x_column = 0, y_column = 1;  // 0-based columns of the CSV file
  std::string title;
  bool points = false;             // marks at the data (a few points), else lines
};

struct XYPanel {
  std::string title, x_label, y_label;
  std::vector<XYCurve> curves;
  bool log_x = false, log_y = false;
  double x_max = 0.0;  // > 0: the x axis ends there
  // the y axis reaches 0: a figure that is constant up to round-off shows
  // flat, not its last digits stretched over the panel
  bool y_includes_zero = false;
};

// The script that draws `panels` from the CSV file `csv_name` (a header row
// first) into `plot_name` (PNG, or SVG by its extension).
std::string XYPlotScript(const std::vector<XYPanel>& panels, const std::string& title, const std::string& csv_name,
                         const std::string& plot_name);

}  // namespace mechflow::cli
