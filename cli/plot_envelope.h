#pragma once
// PlotEnvelope: what a plot of a long run draws instead of every row.
//
// A plot is about a thousand pixels wide; a run may have millions of rows,
// and gnuplot reading them all takes minutes and gigabytes. Passing on each
// row to the results file, this keeps, per bin of time (kBins, each at most a
// pixel column wide), the number of rows, the times of the first and last,
// and for every followed column its smallest and largest value; the run's
// first and last rows are bins of their own, so the plot spans the run
// exactly. Drawn as the band between the min and max lines, every extreme
// shows as it would in a plot of every row. Bins grow by doubling (pairs
// merge) as the run goes, so their number stays between kBins / 2 and kBins
// whatever the run's length and however early it ends.
//
// X-y panels cannot be binned by time; for their columns the rows where one
// of them is smallest or largest in a bin are kept whole, in time order: a
// curve through those rows has every extreme of both coordinates, its path
// between them straightened.

#include <cstdint>
#include <string>
#include <vector>

#include "blocks/outputs/results.h"
#include "diagrams/loader.h"

namespace mechflow::cli {

// The results columns a plot's time panels draw, each once, in order: the
// columns an envelope of them follows.
std::vector<int> PlottedColumns(const std::vector<diagrams::PlotGroup>& groups);
// The 1-based column, in the envelope CSV of `columns`, of `column`'s min.
int EnvelopeMinColumn(const std::vector<int>& columns, int column);

class PlotEnvelope final : public blocks::RowSink {
 public:
  static constexpr int kBins = 2048;

  // `columns`: results columns to envelope (time is column 0, not among
  // them); `xy_columns`: those whose extreme rows x-y panels need. Rows go
  // on to `next` (not owned) first. `t_span`: the run's length, for the
  // first bins' width.
  PlotEnvelope(std::vector<int> columns, std::vector<int> xy_columns, double t_span, blocks::RowSink* next);

  void WriteRow(const double* values, int count) override;
  void set_next(blocks::RowSink* next) { next_ = next; }

  long long rows() const { return rows_; }
  // More rows than twice the bins: the envelope is the smaller to draw.
  bool worthwhile() const { return rows_ > 2LL * kBins; }
  const std::vector<int>& columns() const { return columns_; }
  const std::vector<int>& xy_columns() const { return xy_columns_; }

  // The envelope as CSV: a header (rows,t_first,t_last,time, then "NAME min",
  // "NAME max" per column; `names` are the results' columns), a line per bin
  // in time order; time is where the bin is drawn (between its first and
  // last row). Full precision: every min and max is a value of the results.
  std::string Csv(const std::vector<std::string>& names) const;
  // The envelope CSV's 1-based column of results column `column`'s min (its
  // max is the next one), for a gnuplot script.
  int MinColumn(int column) const { return EnvelopeMinColumn(columns_, column); }

  // The kept rows of the x-y columns as CSV: time, then the xy columns'
  // values, in time order.
  std::string XYCsv(const std::vector<std::string>& names) const;
  // Its 1-based column of results column `column` (an xy column).
  int XYColumn(int column) const;

 private:
  void Fold(const double* values, long long row);
  void Halve();

  std::vector<int> columns_, xy_columns_;
  blocks::RowSink* next_;
  double width_;    // of a bin [s]
  double t0_ = 0.0; // the first row's time: bin 0 starts at the second row
  long long rows_ = 0;
  int last_bin_ = -1;
  std::vector<double> first_, pending_;  // the first row, and the last one seen (not yet in a bin)
  // per bin
  std::vector<long long> count_;
  std::vector<double> t_first_, t_last_;
  std::vector<double> min_, max_;  // bin-major, a value per column
  // per bin and xy column, the rows at its min and max: row number, then
  // time and the xy columns' values
  struct Pick {
    long long row = -1;
    std::vector<double> values;
  };
  std::vector<Pick> picks_;  // bin-major, 2 per xy column (min, max)
};

}  // namespace mechflow::cli
