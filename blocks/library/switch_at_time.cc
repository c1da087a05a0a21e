#include "blocks/library/switch_at_time.h"

namespace mechflow::blocks {

SwitchAtTimeBlock::SwitchAtTimeBlock(const std::string& type, const std::string& name, double switch_time)
    : Block(type, name), switch_time_(switch_time) {
  DeclareOutputPort("y");
  DeclareDiscreteStates(1);
  DeclareZeroCrossing(CrossingDirection::kRising);
}

void SwitchAtTimeBlock::DoInitialize(const BlockContext& ctx) const {
  ctx.discrete()[0] = ctx.time() >= switch_time_ ? 1.0 : 0.0;
}

void SwitchAtTimeBlock::DoCalcZeroCrossings(const BlockContext& ctx) const {
  ctx.zero_crossings()[0] = ctx.time() - switch_time_;
}

void SwitchAtTimeBlock::DoZeroCrossing(int, int, const BlockContext& ctx) const { ctx.discrete()[0] = 1.0; }

bool SwitchAtTimeBlock::DoUpdateModes(const BlockContext& ctx) const {
  const double mode = ctx.time() >= switch_time_ ? 1.0 : 0.0;
  const bool changed = mode != ctx.discrete()[0];
  ctx.discrete()[0] = mode;
  return changed;
}

}  // namespace mechflow::blocks
