#include "graphics/signal_track.h"

#include <algorithm>
#include <cmath>

namespace mechflow::graphics {

namespace {

// Bins over [t_start, t_start + t_span] such that the run's last row, at its
// end, still falls into the last of `bins`.
double FirstBinWidth(double t_span, std::size_t bins) {
  if (!(t_span > 0.0) || !std::isfinite(t_span)) return 1.0;
  return t_span / static_cast<double>(std::max<std::size_t>(1, bins - 1));
}

}  // namespace

SignalTrack::SignalTrack(std::size_t columns, double t_start, double t_span, std::size_t max_points)
    : columns_(columns),
      t_start_(t_start),
      bin_width_(FirstBinWidth(t_span, std::max<std::size_t>(4, max_points) / 2)),
      max_points_(std::max<std::size_t>(4, max_points)) {}

void SignalTrack::Add(double t, const double* values) {
  if (binned_) return AddToBins(t, values);
  times_.push_back(t);
  values_.insert(values_.end(), values, values + columns_);
  if (times_.size() > max_points_) StartBinning();
}

void SignalTrack::StartBinning() {
  binned_ = true;
  for (std::size_t r = 0; r < times_.size(); ++r) AddToBins(times_[r], &values_[r * columns_]);
  times_ = {};
  values_ = {};
}

void SignalTrack::AddToBins(double t, const double* values) {
  const long long index = static_cast<long long>(std::floor((t - t_start_) / bin_width_));
  if (bins_.empty() || index != bins_.back().index) {
    Bin bin{index, t, t, std::vector<Extreme>(columns_)};
    for (std::size_t c = 0; c < columns_; ++c) bin.extremes[c] = {values[c], values[c], t, t};
    bins_.push_back(std::move(bin));
    while (bins_.size() > max_points_ / 2) MergePairs();
    return;
  }
  Bin& bin = bins_.back();
  bin.t_last = t;
  for (std::size_t c = 0; c < columns_; ++c) {
    Extreme& e = bin.extremes[c];
    if (values[c] < e.low) e.low = values[c], e.low_t = t;
    if (values[c] > e.high) e.high = values[c], e.high_t = t;
  }
}

void SignalTrack::MergePairs() {
  bin_width_ *= 2;
  std::vector<Bin> merged;
  for (Bin& bin : bins_) {
    bin.index = static_cast<long long>(std::floor(static_cast<double>(bin.index) / 2));
    if (merged.empty() || merged.back().index != bin.index) {
      merged.push_back(std::move(bin));
      continue;
    }
    Bin& into = merged.back();
    into.t_last = bin.t_last;
    for (std::size_t c = 0; c < columns_; ++c) {
      Extreme& e = into.extremes[c];
      const Extreme& later = bin.extremes[c];
      if (later.low < e.low) e.low = later.low, e.low_t = later.low_t;
      if (later.high > e.high) e.high = later.high, e.high_t = later.high_t;
    }
  }
  bins_ = std::move(merged);
}

std::vector<double> SignalTrack::Times() const {
  if (!binned_) return times_;
  std::vector<double> out;
  for (const Bin& bin : bins_) out.insert(out.end(), {bin.t_first, bin.t_last});
  return out;
}

std::vector<double> SignalTrack::Values() const {
  if (!binned_) return values_;
  std::vector<double> out;
  for (const Bin& bin : bins_) {
    // the extreme that came first at the bin's first row, the other at its last
    for (const Extreme& e : bin.extremes) out.push_back(e.low_t <= e.high_t ? e.low : e.high);
    for (const Extreme& e : bin.extremes) out.push_back(e.low_t <= e.high_t ? e.high : e.low);
  }
  return out;
}

}  // namespace mechflow::graphics
