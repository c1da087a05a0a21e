#pragma once
// Results: the logged signals on the output grid, one row per output time.
//
// By default every row is kept in memory. A run whose rows go to a file as
// they are computed (Stream) keeps only the columns it names, so memory
// stays bounded however long the run; each column's range (smallest and
// largest value and their times) is kept either way.

#include <limits>
#include <ostream>
#include <string>
#include <vector>

#include "blocks/outputs/report.h"

namespace mechflow::blocks {

// Takes each row as it is recorded (a results file). It must not throw: a
// sink that cannot write keeps its error for the end of the run.
class RowSink {
 public:
  virtual ~RowSink() = default;
  virtual void WriteRow(const double* values, int count) = 0;
  // Before the first row: about how many rows the run will make (its output
  // grid, and a last row should it stop early), for a sink that keeps them
  // to allocate once instead of growing row by row.
  virtual void ExpectRows(long rows) { (void)rows; }
};

// The smallest and largest value of a column and the first times they occur.
struct ColumnRange {
  double min = std::numeric_limits<double>::infinity(), min_time = 0.0;
  double max = -std::numeric_limits<double>::infinity(), max_time = 0.0;
};

class Results {
 public:
  // Column 0 is always "time".
  explicit Results(std::vector<std::string> signal_columns);

  const std::vector<std::string>& columns() const { return columns_; }
  int num_columns() const { return static_cast<int>(columns_.size()); }
  int num_rows() const { return rows_; }
  // Index of the named column, or -1.
  int FindColumn(const std::string& name) const;
  // The values of one column: every column when rows are kept, else only
  // the columns Stream was told to keep (std::logic_error otherwise).
  std::vector<double> Column(int column) const;
  double at(int row, int column) const;  // rows kept only
  bool keeps_rows() const { return keep_all_; }
  const ColumnRange& range(int column) const { return ranges_[column]; }
  double last_time() const { return last_time_; }

  // From now on each row goes to `sink` (not owned) and only the columns in
  // `keep` (with time, when any) stay in memory.
  void Stream(RowSink* sink, std::vector<int> keep);

  // Drops the rows and ranges (the streaming set-up stays).
  void Clear();
  void Reserve(int rows);
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
  // full double precision. Rows kept only.
  void WriteCsv(std::ostream& out) const;

 private:
  std::vector<std::string> columns_;
  int rows_ = 0;
  double last_time_ = 0.0;
  std::vector<ColumnRange> ranges_;
  bool keep_all_ = true;
  std::vector<double> values_;               // every column, row after row (keep_all_)
  std::vector<int> kept_;                    // streamed: the columns kept
  std::vector<std::vector<double>> kept_values_;
  RowSink* sink_ = nullptr;
  std::vector<ReportFigure> figures_;
};

// The CSV header line (with its newline) and one row, as WriteCsv writes them.
std::string CsvHeader(const std::vector<std::string>& columns);
void AppendCsvRow(const double* values, int count, std::string* out);

}  // namespace mechflow::blocks
