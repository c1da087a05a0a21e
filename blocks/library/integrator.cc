#include "blocks/library/integrator.h"

#include <algorithm>

namespace mechflow::blocks {

IntegratorBlock::IntegratorBlock(const std::string& name, std::vector<double> initial, std::optional<double> lower,
                                 std::optional<double> upper, ResetKind reset)
    : Block("integrator", name), initial_(std::move(initial)), lower_(lower), upper_(upper), reset_(reset) {
  const int w = static_cast<int>(initial_.size());
  DeclareInputPort("u", w);
  if (reset_ != ResetKind::kNone) {
    DeclareInputPort("reset", 1);
    DeclareInputPort("x0", w);
  }
  DeclareOutputPort("y", w);
  DeclareNoFeedthrough();
  DeclareContinuousStates(w, "x");
  if (has_limits()) {
    DeclareDiscreteStates(w);
    // per element: crossing 2i watches the upper side, 2i+1 the lower side
    for (int i = 0; i < 2 * w; ++i) DeclareZeroCrossing(CrossingDirection::kFalling);
  }
  if (reset_ != ResetKind::kNone) {
    const CrossingDirection d = reset_ == ResetKind::kRising    ? CrossingDirection::kRising
                                : reset_ == ResetKind::kFalling ? CrossingDirection::kFalling
                                                                : CrossingDirection::kEither;
    reset_crossing_ = DeclareZeroCrossing(d);
  }
}

double IntegratorBlock::Clamp(double x) const {
  if (upper_ && x > *upper_) x = *upper_;
  if (lower_ && x < *lower_) x = *lower_;
  return x;
}

double IntegratorBlock::ModeFor(double x, double u) const {
  if (upper_ && x >= *upper_ && u > 0.0) return kAtUpper;
  if (lower_ && x <= *lower_ && u < 0.0) return kAtLower;
  return kFree;
}

void IntegratorBlock::DoInitialize(const BlockContext& ctx) const {
  const auto x = ctx.state();
  for (size_t i = 0; i < x.size(); ++i) x[i] = Clamp(initial_[i]);
  for (double& mode : ctx.discrete()) mode = kFree;  // settled against u by UpdateModes
}

void IntegratorBlock::DoCalcOutput(int, const BlockContext& ctx) const {
  const auto x = ctx.state();
  std::copy(x.begin(), x.end(), ctx.output(0).begin());
}

void IntegratorBlock::DoCalcDerivatives(const BlockContext& ctx) const {
  const auto u = ctx.input(0);
  const auto xdot = ctx.derivative();
  for (size_t i = 0; i < xdot.size(); ++i) xdot[i] = (has_limits() && ctx.discrete()[i] != kFree) ? 0.0 : u[i];
}

void IntegratorBlock::DoCalcZeroCrossings(const BlockContext& ctx) const {
  const auto g = ctx.zero_crossings();
  if (has_limits()) {
    const auto x = ctx.state();
    const auto u = ctx.input(0);
    const auto modes = ctx.discrete();
    for (size_t i = 0; i < x.size(); ++i) {
      // each falls through zero when its event is due; a missing limit never fires
      if (modes[i] == kAtUpper) {
        g[2 * i] = u[i];        // leaves the upper limit when u turns negative
      } else {
        g[2 * i] = upper_ ? *upper_ - x[i] : 1.0;
      }
      if (modes[i] == kAtLower) {
        g[2 * i + 1] = -u[i];   // leaves the lower limit when u turns positive
      } else {
        g[2 * i + 1] = lower_ ? x[i] - *lower_ : 1.0;
      }
    }
  }
  if (reset_crossing_ >= 0) g[reset_crossing_] = ctx.input_scalar(1);
}

void IntegratorBlock::DoZeroCrossing(int index, int, const BlockContext& ctx) const {
  const auto x = ctx.state();
  if (index == reset_crossing_) {
    const auto x0 = ctx.input(2);
    for (size_t i = 0; i < x.size(); ++i) x[i] = Clamp(x0[i]);
    if (has_limits())
      for (size_t i = 0; i < x.size(); ++i) ctx.discrete()[i] = ModeFor(x[i], ctx.input(0)[i]);
    return;
  }
  const size_t i = index / 2;
  double& mode = ctx.discrete()[i];
  const bool upper_side = index % 2 == 0;
  if (mode == kFree) {
    // reached a limit: stop exactly on it
    mode = upper_side ? kAtUpper : kAtLower;
    x[i] = upper_side ? *upper_ : *lower_;
  } else {
    mode = kFree;  // the input turned away from the limit
  }
}

bool IntegratorBlock::DoUpdateModes(const BlockContext& ctx) const {
  if (!has_limits()) return false;
  const auto x = ctx.state();
  const auto u = ctx.input(0);
  bool changed = false;
  for (size_t i = 0; i < x.size(); ++i) {
    double& mode = ctx.discrete()[i];
    const double wanted = ModeFor(x[i], u[i]);
    // enter a limit here only if the state already sits on it; leave when u turned
    if (wanted != mode && (wanted != kFree || mode != kFree)) {
      mode = wanted;
      if (mode != kFree) x[i] = mode == kAtUpper ? *upper_ : *lower_;
      changed = true;
    }
  }
  return changed;
}

}  // namespace mechflow::blocks
