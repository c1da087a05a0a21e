#pragma once
// Integrator: x' = u, y = x, with optional limits and an optional reset.
//
//   inputs:  u (width w); with a reset also `reset` (width 1, the trigger) and
//            `x0` (width w, the value taken at a reset)
//   output:  y = x (width w); no input feeds it directly (x0 is read only at
//            the reset instant, with the values just before it)
//   states:  x (w continuous); with limits one mode per element
//
// Limits (events, not clipping inside a step): while free, a zero crossing of
// upper - x (or x - lower) puts the element in the 'at limit' mode; x is set
// exactly to the limit and x' = 0. It leaves the limit when u changes sign
// away from it (a zero crossing of u).
// Reset: a zero crossing of the `reset` input in the chosen direction (rising,
// falling or either) sets x = x0, then clamps to the limits.

#include <optional>

#include "blocks/block.h"

namespace mechflow::blocks {

enum class ResetKind { kNone, kRising, kFalling, kEither };

class IntegratorBlock : public Block {
 public:
  IntegratorBlock(const std::string& name, std::vector<double> initial, std::optional<double> lower,
                  std::optional<double> upper, ResetKind reset);

 protected:
  void DoInitialize(const BlockContext& ctx) const override;
  void DoCalcOutput(int port, const BlockContext& ctx) const override;
  void DoCalcDerivatives(const BlockContext& ctx) const override;
  void DoCalcZeroCrossings(const BlockContext& ctx) const override;
  void DoZeroCrossing(int index, int direction, const BlockContext& ctx) const override;
  bool DoUpdateModes(const BlockContext& ctx) const override;

 private:
  static constexpr double kFree = 0.0, kAtUpper = 1.0, kAtLower = -1.0;
  bool has_limits() const { return lower_.has_value() || upper_.has_value(); }
  double Clamp(double x) const;
  // mode of an element at x with input u: at a limit only while u pushes into it
  double ModeFor(double x, double u) const;

  std::vector<double> initial_;
  std::optional<double> lower_, upper_;
  ResetKind reset_;
  int reset_crossing_ = -1;  // index of the reset's zero crossing
};

}  // namespace mechflow::blocks
