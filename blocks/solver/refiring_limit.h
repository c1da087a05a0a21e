#pragma once
// RefiringLimit: a crossing that fires again and again at one instant is a
// modelling error (a handler that leaves it where it fires again). CVODE
// locates each refiring a hair after the last, never at the very same t, so
// "one instant" is a run of firings of one crossing, each within
// kInstant * max(1, |t|) seconds of the one before.

#include <vector>

namespace mechflow::blocks {

class RefiringLimit {
 public:
  static constexpr int kMaxEventsPerInstant = 100;
  static constexpr double kInstant = 1e-9;

  // A new run with `crossings` crossing functions, none fired yet.
  void Reset(int crossings);
  // Counts a firing of crossing i at t; false when it has now fired more
  // than kMaxEventsPerInstant times at one instant.
  bool Fire(int i, double t);

 private:
  std::vector<double> last_fired_;   // per crossing: when it last fired
  std::vector<int> fired_in_a_row_;  // per crossing: firings in its current instant
};

}  // namespace mechflow::blocks
