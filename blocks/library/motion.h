#pragma once
// Motion sources: a position with its first two time derivatives, the
// signal that drives a prescribed joint coordinate (an <et type="tt"/"rt">
// with signal="NAME" in a mechanism; its port NAME takes these three).
//
//   output y (width 3): q, q', q'' -- consistent by construction, so the
//   mechanism's velocities and accelerations follow the position exactly
//
//   motion_sine    q = bias + amplitude sin(2 pi frequency t + phase)
//   motion_table   q = f(s), s = start + speed t: a table of breakpoints s
//                  (time, or distance travelled at `speed`, as a road profile)
//                  with interpolation cubic (default: continuous q'') or
//                  linear/step, extrapolation hold/linear/error
//                  (blocks/library/interpolation.h); q' = speed f'(s),
//                  q'' = speed^2 f''(s). Corners are events (AxisModes).
//   motion_filter  q'' = w^2 (u - q) - 2 zeta w q', w = 2 pi frequency: any
//                  signal u made a motion by a second-order filter (zeta = 1:
//                  critically damped, no overshoot). States q, q'; it starts
//                  at rest at u(t_start). q'' reads u: the output feeds
//                  through from u.
//
// A drive's acceleration enters the dynamics directly (as a prescribed
// motion's does), so a position signal without consistent derivatives --
// differenced, or a step -- cannot drive a joint; motion_filter is the way
// to drive from such a signal.

#include <numbers>
#include <string>
#include <vector>

#include "blocks/framework/block.h"
#include "blocks/library/interpolation.h"

namespace mechflow::blocks {

class MotionSineBlock final : public Block {
 public:
  MotionSineBlock(const std::string& name, double amplitude, double frequency, double phase, double bias);

 private:
  void DoCalcOutput(int port, const BlockContext& ctx) const override;
  double OwnTimeScale() const override { return 2.0 * std::numbers::pi / std::abs(omega_); }  // the period
  double amplitude_, omega_, phase_, bias_;
};

class MotionTableBlock final : public Block {
 public:
  MotionTableBlock(const std::string& name, Axis axis, std::vector<double> values, double start, double speed);

  std::string CrossingName(int index, int) const override { return modes_.CrossingName(index, {"s"}); }
 private:
  void DoInitialize(const BlockContext& ctx) const override;
  void DoCalcOutput(int port, const BlockContext& ctx) const override;
  void DoCalcZeroCrossings(const BlockContext& ctx) const override;
  void DoZeroCrossing(int index, int direction, const BlockContext& ctx) const override;
  bool DoUpdateModes(const BlockContext& ctx) const override;
  double Argument(const BlockContext& ctx) const;  // s = start + speed t

  Axis axis_;
  Curve curve_;
  AxisModes modes_;
  double start_, speed_;
};

class MotionFilterBlock final : public Block {
 public:
  MotionFilterBlock(const std::string& name, double frequency, double damping);

 private:
  void DoInitialize(const BlockContext& ctx) const override;
  void DoCalcOutput(int port, const BlockContext& ctx) const override;
  void DoCalcDerivatives(const BlockContext& ctx) const override;
  bool DoUpdateModes(const BlockContext& ctx) const override;
  double Acceleration(const BlockContext& ctx) const;

  double omega_, damping_;
};

}  // namespace mechflow::blocks
