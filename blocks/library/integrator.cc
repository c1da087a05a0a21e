#include "blocks/library/integrator.h"

#include "blocks/library/hysteresis.h"

#include <algorithm>

namespace mechflow::blocks {
namespace {

// Trigger sign before the first UpdateModes (inputs are not valid in Initialize).
constexpr double kSignUnknown = 2.0;

double Sign(double v) { return v > 0.0 ? 1.0 : v < 0.0 ? -1.0 : 0.0; }

}  // namespace

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
    for (int i = 0; i < 2 * w; ++i) DeclareZeroCrossing(CrossingDirection::kEither);
  }
  if (reset_ != ResetKind::kNone) {
    trigger_sign_ = has_limits() ? w : 0;
    DeclareDiscreteStates(1);
    reset_crossing_ = DeclareZeroCrossing(reset_ == ResetKind::kRising    ? CrossingDirection::kRising
                                          : reset_ == ResetKind::kFalling ? CrossingDirection::kFalling
                                                                          : CrossingDirection::kEither);
  }
}

double IntegratorBlock::Clamp(double x) const {
  if (upper_ && x > *upper_) x = *upper_;
  if (lower_ && x < *lower_) x = *lower_;
  return x;
}

double IntegratorBlock::LimitMode(double x, double u) const {
  // on a limit: held while u pushes into it, exact while u rests on 0 (within
  // the hysteresis band), free when it pulls away
  const double band = CornerBand(0.0);
  if (upper_ && x >= *upper_) return u > band ? kAtUpper : u >= -band ? kExactUpper : kFree;
  if (lower_ && x <= *lower_) return u < -band ? kAtLower : u <= band ? kExactLower : kFree;
  return kFree;
}

void IntegratorBlock::Reset(const BlockContext& ctx) const {
  const auto x = ctx.state();
  const auto x0 = ctx.input(2);
  const auto u = ctx.input(0);
  for (size_t i = 0; i < x.size(); ++i) {
    x[i] = Clamp(x0[i]);
    if (has_limits()) ctx.discrete()[i] = LimitMode(x[i], u[i]);
  }
}

void IntegratorBlock::DoInitialize(const BlockContext& ctx) const {
  std::copy(initial_.begin(), initial_.end(), ctx.state().begin());
  // modes and the trigger's sign are settled against the inputs by UpdateModes
  if (has_limits())
    for (size_t i = 0; i < initial_.size(); ++i) ctx.discrete()[i] = kFree;
  if (trigger_sign_ >= 0) ctx.discrete()[trigger_sign_] = kSignUnknown;
}

void IntegratorBlock::DoCalcOutput(int, const BlockContext& ctx) const {
  const auto x = ctx.state();
  std::copy(x.begin(), x.end(), ctx.output(0).begin());
}

void IntegratorBlock::DoCalcDerivatives(const BlockContext& ctx) const {
  const auto u = ctx.input(0);
  const auto xdot = ctx.derivative();
  if (!has_limits()) {
    std::copy(u.begin(), u.end(), xdot.begin());
    return;
  }
  const auto modes = ctx.discrete();
  for (size_t i = 0; i < xdot.size(); ++i) {
    const double mode = modes[i];
    xdot[i] = mode == kFree          ? u[i]
              : mode == kExactUpper ? std::min(u[i], 0.0)
              : mode == kExactLower ? std::max(u[i], 0.0)
                                    : 0.0;
  }
}

void IntegratorBlock::DoCalcZeroCrossings(const BlockContext& ctx) const {
  const auto g = ctx.zero_crossings();
  if (has_limits()) {
    const auto x = ctx.state();
    const auto u = ctx.input(0);
    const auto modes = ctx.discrete();
    for (size_t i = 0; i < x.size(); ++i) {
      // at a limit u pulling away past the band is the event; free, reaching
      // the limit (a missing one never fires)
      const bool at_upper = modes[i] == kAtUpper || modes[i] == kExactUpper;
      const bool at_lower = modes[i] == kAtLower || modes[i] == kExactLower;
      const double band = CornerBand(0.0);
      g[2 * i] = at_upper ? u[i] + band : upper_ ? *upper_ - x[i] : 1.0;
      g[2 * i + 1] = at_lower ? u[i] - band : lower_ ? x[i] - *lower_ : 1.0;
    }
  }
  if (reset_crossing_ >= 0) g[reset_crossing_] = ctx.input_scalar(1);
}

std::string IntegratorBlock::CrossingName(int index, int direction) const {
  if (index == reset_crossing_) return std::string("reset trigger ") + (direction > 0 ? "rises" : "falls");
  const std::string x = initial_.size() > 1 ? "x[" + std::to_string(index / 2) + "]" : "x";
  return x + (index % 2 == 0 ? ": upper" : ": lower") + " limit reached or left";
}

void IntegratorBlock::DoZeroCrossing(int index, int direction, const BlockContext& ctx) const {
  if (index == reset_crossing_) {
    // inputs hold their values just before the event: x0 is read there
    if ((direction > 0 && fires_rising()) || (direction < 0 && fires_falling())) Reset(ctx);
    ctx.discrete()[trigger_sign_] = Sign(ctx.input_scalar(1));
    return;
  }
  const auto x = ctx.state();
  const size_t i = index / 2;
  double& mode = ctx.discrete()[i];
  const bool upper_side = index % 2 == 0;
  if (mode != kFree) {
    // u changed sign at the limit: free; UpdateModes holds it again if u still pushes
    mode = kFree;
  } else if (direction < 0) {
    // reached the limit: stop exactly on it
    mode = upper_side ? kAtUpper : kAtLower;
    x[i] = upper_side ? *upper_ : *lower_;
  }
}

bool IntegratorBlock::DoUpdateModes(const BlockContext& ctx) const {
  bool changed = false;
  if (trigger_sign_ >= 0) {
    // a trigger that jumped across zero at this event (no crossing saw it)
    double& last = ctx.discrete()[trigger_sign_];
    const double now = Sign(ctx.input_scalar(1));
    if (last != kSignUnknown && now != last) {
      const bool fires = (fires_rising() && last <= 0.0 && now > 0.0) || (fires_falling() && last >= 0.0 && now < 0.0);
      if (fires) {
        Reset(ctx);
        changed = true;
      }
    }
    last = now;
  }
  if (!has_limits()) return changed;
  const auto x = ctx.state();
  const auto u = ctx.input(0);
  for (size_t i = 0; i < x.size(); ++i) {
    double& mode = ctx.discrete()[i];
    const double wanted = LimitMode(x[i], u[i]);
    if (wanted == mode) continue;
    mode = wanted;
    // entering a limit here only happens with x already on it: make it exact
    if (mode == kAtUpper || mode == kExactUpper) x[i] = *upper_;
    if (mode == kAtLower || mode == kExactLower) x[i] = *lower_;
    changed = true;
  }
  return changed;
}

}  // namespace mechflow::blocks
