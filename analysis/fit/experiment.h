#pragma once
// An experiment of a fit: a measured data file, the diagram's signals matched
// to its columns, and the variants and --set values the diagram runs with to
// reproduce that test.
//
// The data file is a CSV with a header and time [s] in its first column (as
// run/results_table.h reads it: rising times, every field a finite number,
// file:line for a bad row). The diagram is run with rows at exactly the
// measured times (RunOptions::times): the residuals compare the solver's
// own output at each measured instant, with no interpolation.

#include <string>
#include <utility>
#include <vector>

namespace mechflow::analysis::fit {

// --match SIGNAL=COLUMN[:WEIGHT]: the diagram's output port SIGNAL
// ("block.port", "block.port[i]") against the data's COLUMN, each
// difference multiplied by WEIGHT (default 1; 1/sigma for a noise sigma).
// SIGNAL "report:LABEL" is the value of the diagram's <report> LABEL (a peak
// force), "report-time:LABEL" its time: one residual per experiment, against
// the one value of COLUMN in the data file.
struct Match {
  enum class Kind { kSignal, kFigureValue, kFigureTime };
  std::string signal, column;
  double weight = 1.0;
  Kind kind = Kind::kSignal;
  std::string figure;  // the <report> label of a figure's match
  bool is_signal() const { return kind == Kind::kSignal; }
};

// Throws InputError saying what is wrong.
Match ParseMatch(const std::string& text);

struct Experiment {
  std::string file;  // the data file, for messages and outputs
  std::vector<std::string> variants;                      // --variant after its --data
  std::vector<std::pair<std::string, double>> overrides;  // --set NAME=VALUE after its --data
  std::vector<double> times;                              // measured instants, rising
  std::vector<std::vector<double>> measured;              // per match, at `times` (a figure's: its one value)
  std::vector<int> lines;                                 // each time's line in the file
};

// Reads `text` (the file `path`) for the columns of `matches`. Throws
// InputError naming path:line (a bad row, a time not after the one before,
// a missing column, a figure's column whose rows differ), or the file when
// it has no rows.
Experiment ReadExperiment(const std::string& text, const std::string& path, const std::vector<Match>& matches);

// Checks that every measured time lies in [t_start, t_end] of the run;
// InputError naming the file's line of the first that does not.
void CheckTimesInRun(const Experiment& experiment, double t_start, double t_end);

}  // namespace mechflow::analysis::fit
