#include "blocks/library/clock.h"

namespace mechflow::blocks {

ClockBlock::ClockBlock(const std::string& name) : Block("clock", name) { DeclareOutputPort("y"); }

void ClockBlock::DoCalcOutput(int, const BlockContext& ctx) const { ctx.output(0)[0] = ctx.time(); }

}  // namespace mechflow::blocks
