#pragma once
// Output and sample times on a grid t0 + k * interval, computed from the
// integer k (no drift over long runs) and read as the decimals they stand for.

#include <utility>
#include <vector>

namespace mechflow::blocks {

// An output (or sample) time t0 + k * interval as the decimal it stands for: the
// product rounds (47 * 0.01 = 0.47000000000000003), and a row taken there
// would read so in the results. The double nearest the time's 15 significant
// digits, when it is within a few units in the last place of it (rounding,
// not a grid of its own such as k / 3), so the row is taken at 0.47 and the
// results, in the shortest form that reads back, show 0.47.
double DecimalGridTime(double t);

// The output times of a run: t0 + k * interval as decimals, never past t_end;
// or, when `times` is not empty, those instants (increasing, in [t0, t_end])
// and no row after the last.
class OutputGrid {
 public:
  OutputGrid(double t0, double interval, double t_end, std::vector<double> times = {})
      : t0_(t0), interval_(interval), t_end_(t_end), times_(std::move(times)) {}
  // The k-th output time (k = 0 first); infinity past the last given time.
  double Time(long k) const;
  // How many rows the grid asks for.
  long Count() const;

 private:
  double t0_, interval_, t_end_;
  std::vector<double> times_;
};

}  // namespace mechflow::blocks
