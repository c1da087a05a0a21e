#pragma once
// Results: the logged signals on the output grid, one row per output time.

#include <ostream>
#include <string>
#include <vector>

#include "blocks/report.h"

namespace mechflow::blocks {

class Results {
 public:
  // Column 0 is always "time".
  explicit Results(std::vector<std::string> signal_columns);

  const std::vector<std::string>& columns() const { return columns_; }
  int num_columns() const { return static_cast<int>(columns_.size()); }
  int num_rows() const { return static_cast<int>(values_.size() / columns_.size()); }
  double at(int row, int column) const { return values_[row * columns_.size() + column]; }
  // Index of the named column, or -1.
  int FindColumn(const std::string& name) const;
  // All values of one column.
  std::vector<double> Column(int column) const;

  void Reserve(int rows) { values_.reserve(rows * columns_.size()); }
  // Appends a row: `values` holds num_columns() numbers, time first.
  void AddRow(const double* values);

  // The figures of the diagram's <report>s, in their order.
  const std::vector<ReportFigure>& figures() const { return figures_; }
  void SetFigures(std::vector<ReportFigure> figures) { figures_ = std::move(figures); }
  // label,kind,signal,value,unit,time: one line per figure (empty value and
  // time when not found); full double precision. (Files are written by the
  // CLI's OutputFolder, which checks every write.)
  void WriteFiguresCsv(std::ostream& out) const;

  // CSV with a header line (a label holding a comma or quote is quoted);
  // full double precision.
  void WriteCsv(std::ostream& out) const;

 private:
  std::vector<std::string> columns_;
  std::vector<double> values_;
  std::vector<ReportFigure> figures_;
};

}  // namespace mechflow::blocks
