#include "blocks/library/ramp.h"

namespace mechflow::blocks {

RampBlock::RampBlock(const std::string& name, double slope, double start, double initial)
    : SwitchAtTimeBlock("ramp", name, start), slope_(slope), initial_(initial) {}

void RampBlock::DoCalcOutput(int, const BlockContext& ctx) const {
  ctx.output(0)[0] = initial_ + (switched(ctx) ? slope_ * (ctx.time() - switch_time()) : 0.0);
}

}  // namespace mechflow::blocks
