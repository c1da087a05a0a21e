#pragma once
// The refusal of frozen motion: when CVODE's own time advanced between two
// rows (no re-initialisation between) while its own state stayed the same bit
// for bit, although its derivative there is not zero, the step size fell
// below the resolution of time. Such rows are refused (SimulationError)
// rather than written.

#include <span>
#include <vector>

namespace mechflow::blocks {

class CvodeRun;

// Frozen motion: the same state bit for bit `dt` seconds apart although the
// slope would have moved component i by more than a thousandth of its error
// weight. Returns the first such i, or -1.
int FrozenState(std::span<const double> before, std::span<const double> after, std::span<const double> slope,
                double dt, double rtol, double atol);

class FrozenMotionGuard {
 public:
  // For `states` continuous states (none: nothing can freeze).
  FrozenMotionGuard(int states, double rtol, double atol);

  // A new start: the history compared against is gone.
  void Forget() { valid_ = false; }
  // Before a row: compares CVODE's state now with the one at the last row;
  // throws SimulationError on frozen motion.
  void Check(const CvodeRun& cvode);

 private:
  double rtol_, atol_;
  std::vector<double> y_, before_, slope_;  // CVODE's state at the last row, scratch
  double tn_ = 0.0;                         // and its time
  bool valid_ = false;
};

}  // namespace mechflow::blocks
