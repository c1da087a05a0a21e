#pragma once
// Step: y = before for t < time, y = after for t >= time.
//
//   ports:   no inputs; output y (width 1)
//   params:  time [s] (0), before (0), after (1), in the unit of the signal
// Events: the switch is a zero crossing of t - time with a mode (see
// switch_at_time.h), so y jumps exactly at the located instant and is
// constant inside every solver step.

#include <string>

#include "blocks/library/switch_at_time.h"

namespace mechflow::blocks {

class StepBlock : public SwitchAtTimeBlock {
 public:
  StepBlock(const std::string& name, double time, double before, double after);

 protected:
  void DoCalcOutput(int port, const BlockContext& ctx) const override;

 private:
  double before_, after_;
};

}  // namespace mechflow::blocks
