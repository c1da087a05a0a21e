#pragma once
// Output and sample times on a grid t0 + k * interval, computed from the
// integer k (no drift over long runs) and read as the decimals they stand for.

namespace mechflow::blocks {

// An output (or sample) time t0 + k * interval as the decimal it stands for: the
// product rounds (47 * 0.01 = 0.47000000000000003), and a row taken there
// would read so in the results. The double nearest the time's 15 significant
// digits, when it is within a few units in the last place of it (rounding,
// not a grid of its own such as k / 3), so the row is taken at 0.47 and the
// results, in the shortest form that reads back, show 0.47.
double DecimalGridTime(double t);

// The output times of a run: t0 + k * interval as decimals, never past t_end.
class OutputGrid {
 public:
  OutputGrid(double t0, double interval, double t_end) : t0_(t0), interval_(interval), t_end_(t_end) {}
  double Time(long k) const;

 private:
  double t0_, interval_, t_end_;
};

}  // namespace mechflow::blocks
