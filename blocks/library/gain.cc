#include "blocks/library/gain.h"

namespace mechflow::blocks {

GainBlock::GainBlock(const std::string& name, double k, int width) : Block("gain", name), k_(k) {
  DeclareInputPort("u", width);
  DeclareOutputPort("y", width);
}

void GainBlock::DoCalcOutput(int, const BlockContext& ctx) const {
  const auto u = ctx.input(0);
  const auto y = ctx.output(0);
  for (size_t i = 0; i < y.size(); ++i) y[i] = k_ * u[i];
}

}  // namespace mechflow::blocks
