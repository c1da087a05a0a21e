#include "blocks/solver/refiring_limit.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mechflow::blocks {

void RefiringLimit::Reset(int crossings) {
  last_fired_.assign(crossings, -std::numeric_limits<double>::infinity());
  fired_in_a_row_.assign(crossings, 0);
}

bool RefiringLimit::Fire(int i, double t) {
  const double instant = kInstant * std::max(1.0, std::abs(t));
  fired_in_a_row_[i] = t - last_fired_[i] <= instant ? fired_in_a_row_[i] + 1 : 1;
  last_fired_[i] = t;
  return fired_in_a_row_[i] <= kMaxEventsPerInstant;
}

}  // namespace mechflow::blocks
