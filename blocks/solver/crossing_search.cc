#include "blocks/solver/crossing_search.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace mechflow::blocks {

CrossingSearch::CrossingSearch(std::vector<int> directions)
    : directions_(std::move(directions)),
      active_(directions_.size(), 1),
      g_lo_(directions_.size(), 0.0),
      bracket_lo_(directions_.size(), 0.0),
      bracket_hi_(directions_.size(), 0.0),
      trial_(directions_.size(), 0.0),
      found_(directions_.size(), 0) {}

void CrossingSearch::Start(double t, std::span<const double> g) {
  t_lo_ = t;
  inactive_ = 0;
  for (int i = 0; i < size(); ++i) {
    g_lo_[i] = g[i];
    active_[i] = g[i] != 0.0;
    inactive_ += !active_[i];
  }
}

bool CrossingSearch::AnyInactive() const { return inactive_ > 0; }

void CrossingSearch::Probe(std::span<const double> g) {
  for (int i = 0; i < size(); ++i) {
    if (active_[i] || g[i] == 0.0) continue;
    active_[i] = 1;
    --inactive_;
    g_lo_[i] = g[i];
  }
}

int CrossingSearch::Leader(std::span<const double> lo, std::span<const double> hi, bool* zero) const {
  int leader = -1;
  double largest = 0.0;
  *zero = false;
  for (int i = 0; i < size(); ++i) {
    if (!active_[i] || !Counts(i, lo[i])) continue;
    if (hi[i] == 0.0) {
      *zero = true;
    } else if (lo[i] * hi[i] < 0.0) {
      // the secant's root lies this fraction of the bracket below its upper end
      const double fraction = std::abs(hi[i] / (hi[i] - lo[i]));
      if (fraction > largest) largest = fraction, leader = i;
    }
  }
  return leader;
}

bool CrossingSearch::Crosses(std::span<const double> g) const {
  // Leader's test without its fractions, the rare sign change first: this
  // runs at every check
  const double* lo = g_lo_.data();
  const double* hi = g.data();
  for (int i = 0, n = size(); i < n; ++i)
    if ((hi[i] == 0.0 || lo[i] * hi[i] < 0.0) && active_[i] && Counts(i, lo[i])) return true;
  return false;
}

void CrossingSearch::Accept(double t, std::span<const double> g) {
  t_lo_ = t;
  std::copy(g.begin(), g.end(), g_lo_.begin());
  if (inactive_ == 0) return;
  for (int i = 0; i < size(); ++i)
    if (!active_[i] && g[i] != 0.0) active_[i] = 1, --inactive_;
}

double CrossingSearch::Locate(double t_hi, std::span<const double> g_hi, double ttol,
                              const std::function<void(double, std::span<double>)>& g_at) {
  // the bracket (t_lo, t_hi] narrows on copies: the lower end of the
  // search stays as it was until the caller accepts or starts anew
  std::vector<double>&lo = bracket_lo_, &hi = bracket_hi_, &mid = trial_;
  std::copy(g_lo_.begin(), g_lo_.end(), lo.begin());
  std::copy(g_hi.begin(), g_hi.end(), hi.begin());
  double t_lo = t_lo_;
  bool zero = false;
  int leader = Leader(lo, hi, &zero);
  // leader < 0: no sign change, only an exact zero at t_hi, which is the crossing
  double alpha = 1.0;
  int side = 0, side_before = -1;  // 1: the last bracket was the lower part, 2: the upper
  while (leader >= 0 && std::abs(t_hi - t_lo) > ttol) {
    // a side kept twice in a row weighs half (Illinois); else the plain secant
    alpha = side_before != side ? 1.0 : side == 2 ? 2.0 * alpha : 0.5 * alpha;
    double t_mid = t_hi - (t_hi - t_lo) * hi[leader] / (hi[leader] - alpha * lo[leader]);
    // not closer than half the tolerance to either end
    const auto inward = [&] {
      const double intervals = std::abs(t_hi - t_lo) / ttol;
      return intervals > 5.0 ? 0.1 : 0.5 / intervals;
    };
    if (std::abs(t_mid - t_lo) < 0.5 * ttol) t_mid = t_lo + inward() * (t_hi - t_lo);
    if (std::abs(t_hi - t_mid) < 0.5 * ttol) t_mid = t_hi - inward() * (t_hi - t_lo);
    g_at(t_mid, mid);
    ++evaluations_;
    side_before = side;
    const int next = Leader(lo, mid, &zero);
    if (next >= 0) {  // the sign changes below t_mid
      t_hi = t_mid;
      std::swap(hi, mid);
      leader = next;
      side = 1;
    } else if (zero) {  // no sign change below, but a zero at t_mid: the crossing
      t_hi = t_mid;
      std::swap(hi, mid);
      break;
    } else {  // the sign changes above t_mid
      t_lo = t_mid;
      std::copy(mid.begin(), mid.end(), lo.begin());
      side = 2;
    }
  }
  for (int i = 0; i < size(); ++i) {
    found_[i] = 0;
    if (!active_[i] || !Counts(i, lo[i])) continue;
    if (hi[i] == 0.0 || lo[i] * hi[i] < 0.0) found_[i] = lo[i] > 0.0 ? -1 : 1;
  }
  return t_hi;
}

}  // namespace mechflow::blocks
