#include "blocks/solver/grid_time.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>

namespace mechflow::blocks {

double DecimalGridTime(double t) {
  char text[32];
  const auto end = std::to_chars(text, text + sizeof text, t, std::chars_format::general, 15).ptr;
  double decimal = t;
  std::from_chars(text, end, decimal);
  const double ulp = std::nextafter(std::abs(t), std::numeric_limits<double>::infinity()) - std::abs(t);
  return std::abs(decimal - t) <= 4.0 * ulp ? decimal : t;
}

double OutputGrid::Time(long k) const {
  if (!times_.empty())
    return k < static_cast<long>(times_.size()) ? times_[k] : std::numeric_limits<double>::infinity();
  return std::min(DecimalGridTime(t0_ + k * interval_), t_end_);
}

long OutputGrid::Count() const {
  if (!times_.empty()) return static_cast<long>(times_.size());
  return std::lround((t_end_ - t0_) / interval_) + 1;
}

}  // namespace mechflow::blocks
