#pragma once
// Table: y = piecewise-linear interpolation in t of points (t_i, y_i).
//
//   ports:   no inputs; output y (width 1)
//   params:  points  inline rows "t0 y0; t1 y1; ..." [s, unit], or
//            file    a CSV file of rows t, y (exactly one of the two)
//
//   y(t) = y_i + (t - t_i) (y_{i+1} - y_i) / (t_{i+1} - t_i)  for t_i <= t < t_{i+1}
//   y(t) = y_0 for t <= t_0 and y_n for t >= t_n: held constant beyond the
//   ends, not extrapolated.
//
// Times must increase strictly, with at least two points. The CSV file has
// two numeric columns separated by commas or whitespace, optional '#'
// comments and at most one non-numeric header line before the data.
// The corners at t_i are not events (the output is continuous); bound the
// solver's step (max_step) if a table with sharp corners drives a state.
// Run time: a binary search (std::upper_bound) per evaluation, no state.

#include <string>
#include <vector>

#include "blocks/framework/block.h"

namespace mechflow::blocks {

class TableBlock : public Block {
 public:
  // `times` strictly increasing, at least two points, as many values.
  TableBlock(const std::string& name, std::vector<double> times, std::vector<double> values);

 protected:
  void DoCalcOutput(int port, const BlockContext& ctx) const override;

 private:
  std::vector<double> times_, values_;
};

// Reads the points of a `points` parameter (rows of two numbers, the
// argument named `x` in messages). Throws InputError naming the offending
// row ("points row 3: ...").
void TablePointsFromRows(const std::vector<std::vector<double>>& rows, std::vector<double>* times,
                         std::vector<double>* values, const std::string& x = "t");

// One line of numbers of a table file, and its line number. `header`: the
// first line, whose first field was not a number (a corner label, as in the
// first line of a 2-D table: "x\\y, 0, 1, 2"); that field reads as NaN.
struct NumberRow {
  int line = 0;
  std::vector<double> values;
  bool header = false;
};

// The lines of numbers of a table file's `text` (read by the loader, which
// confines it to the diagram's folder: blocks/support/input_file.h): fields separated
// by commas, semicolons, tabs or spaces, '#' comments, blank lines skipped, a
// byte-order mark ignored, and at most one header line before the data,
// either all text (skipped) or a corner label and numbers (kept, `header`).
// InputError "path:line: expected EXPECTED, found '...'" (an excerpt) for
// text after that.
std::vector<NumberRow> ReadNumberRows(const std::string& text, const std::string& path, const std::string& expected);

// Reads the points of a CSV file's `text` as described above. Throws
// InputError naming path:line for a bad row, or the path when the file is
// unusable as a whole.
void ReadTableCsv(const std::string& text, const std::string& path, std::vector<double>* times,
                  std::vector<double>* values, const std::string& x = "t");

}  // namespace mechflow::blocks
