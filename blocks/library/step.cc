#include "blocks/library/step.h"

namespace mechflow::blocks {

StepBlock::StepBlock(const std::string& name, double time, double before, double after)
    : SwitchAtTimeBlock("step", name, time), before_(before), after_(after) {}

void StepBlock::DoCalcOutput(int, const BlockContext& ctx) const {
  ctx.output(0)[0] = switched(ctx) ? after_ : before_;
}

}  // namespace mechflow::blocks
