#pragma once
// Integrator: x' = u, y = x, with optional limits and an optional reset.
//
//   inputs:  u (width w); with a reset also `reset` (width 1, the trigger) and
//            `x0` (width w, the value taken at a reset)
//   output:  y = x (width w); no input feeds it directly (x0 is read only at
//            the reset instant, with the values just before it)
//   states:  x (w continuous); with limits one mode per element; with a reset
//            the sign of the trigger seen at the last event
//   params:  initial x(t_start) (one value, or one per element; within the
//            limits), lower, upper (optional, lower < upper), width w, reset
//            (none, rising, falling, either)
//
// Limits (events, not clipping inside a step): while free, a zero crossing of
// upper - x (or x - lower) puts the element in the 'at limit' mode; x is set
// exactly to the limit and x' = 0. It leaves the limit when u pulls away
// past the hysteresis band of blocks/library/hysteresis.h (a zero crossing
// of u plus or minus the band), so an input resting on 0 with round-off
// noise does not chatter. After every event the mode is re-classified from
// x and u, which also handles an input that jumped: on a limit and pushing
// into it -> at the limit, pulling away -> free.
// Tie: x on a limit with u within the band of 0 gives the mode 'at limit,
// exact', where x' = min(u, 0) at the upper limit (max(u, 0) at the lower),
// so x stays or leaves correctly whichever way u goes.
//
// Reset: `rising` fires when the trigger goes from <= 0 to > 0, `falling` from
// >= 0 to < 0, `either` on both. A continuous crossing is a zero crossing of
// the trigger (x0 is read as it was just before the event). A trigger that
// jumps across zero at another block's event or sample hit (a step, a
// sample_hold) is caught right after that event by UpdateModes, which
// compares the trigger's sign with the one kept from the last event; x0 is
// then read after the event. After a reset x = x0, clamped to the limits.
// Blind spots, as the block sees the trigger only at events: (1) a trigger
// that is exactly 0 where an integration starts and leaves 0 continuously
// gives no crossing; (2) after a continuous crossing against the trigger
// direction (not an event), or after (1), the kept sign is stale, so a jump
// at a later event may be taken wrongly. Keep triggers off exactly 0 while
// they move continuously.

#include <optional>

#include "blocks/framework/block.h"

namespace mechflow::blocks {

enum class ResetKind { kNone, kRising, kFalling, kEither };

class IntegratorBlock : public Block {
 public:
  // `initial` has one value per element and lies within the limits (checked
  // by the factory).
  IntegratorBlock(const std::string& name, std::vector<double> initial, std::optional<double> lower,
                  std::optional<double> upper, ResetKind reset);

 protected:
  void DoInitialize(const BlockContext& ctx) const override;
  std::string CrossingName(int index, int direction) const override;
  void DoCalcOutput(int port, const BlockContext& ctx) const override;
  void DoCalcDerivatives(const BlockContext& ctx) const override;
  void DoCalcZeroCrossings(const BlockContext& ctx) const override;
  void DoZeroCrossing(int index, int direction, const BlockContext& ctx) const override;
  bool DoUpdateModes(const BlockContext& ctx) const override;

 private:
  // limit modes; the exact ones are ties (on the limit with u exactly 0)
  static constexpr double kFree = 0.0, kAtUpper = 1.0, kAtLower = -1.0, kExactUpper = 2.0, kExactLower = -2.0;
  bool has_limits() const { return lower_.has_value() || upper_.has_value(); }
  bool fires_rising() const { return reset_ == ResetKind::kRising || reset_ == ResetKind::kEither; }
  bool fires_falling() const { return reset_ == ResetKind::kFalling || reset_ == ResetKind::kEither; }
  double Clamp(double x) const;
  // The limit mode of an element from x and u (x within the limits).
  double LimitMode(double x, double u) const;
  // x = x0 (clamped) and the limit modes that go with it.
  void Reset(const BlockContext& ctx) const;

  std::vector<double> initial_;
  std::optional<double> lower_, upper_;
  ResetKind reset_;
  int reset_crossing_ = -1;  // zero crossing of the trigger, or -1
  int trigger_sign_ = -1;    // discrete state: sign of the trigger at the last event, or -1
};

}  // namespace mechflow::blocks
