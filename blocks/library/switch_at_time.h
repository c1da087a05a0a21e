#pragma once
// SwitchAtTimeBlock: the common part of step and ramp, an output that changes
// its formula at one instant.
//
// One discrete state, the mode (0 before the switch time, 1 from it on), and
// one zero crossing g = t - switch_time (rising). The output is computed from
// the mode, never from t < switch_time directly, so the solver's steps never
// straddle the switch: the step or corner sits exactly at the located event.
// Initialize sets the mode from t_start; UpdateModes keeps it equal to
// (t >= switch_time) after every event.

#include <string>

#include "blocks/framework/block.h"

namespace mechflow::blocks {

class SwitchAtTimeBlock : public Block {
 public:
  // Declares the output port y (width 1), the mode and the zero crossing.
  SwitchAtTimeBlock(const std::string& type, const std::string& name, double switch_time);

 protected:
  bool switched(const BlockContext& ctx) const { return ctx.discrete()[0] != 0.0; }
  double switch_time() const { return switch_time_; }
  void DoInitialize(const BlockContext& ctx) const override;
  void DoCalcZeroCrossings(const BlockContext& ctx) const override;
  void DoZeroCrossing(int index, int direction, const BlockContext& ctx) const override;
  bool DoUpdateModes(const BlockContext& ctx) const override;

 private:
  double switch_time_;  // [s]
};

}  // namespace mechflow::blocks
