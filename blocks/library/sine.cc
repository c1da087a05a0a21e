#include "blocks/library/sine.h"

#include <cmath>
#include <numbers>

namespace mechflow::blocks {

SineBlock::SineBlock(const std::string& name, double amplitude, double frequency, double phase, double bias)
    : Block("sine", name),
      amplitude_(amplitude),
      omega_(2.0 * std::numbers::pi * frequency),
      phase_(phase),
      bias_(bias) {
  DeclareOutputPort("y");
}

void SineBlock::DoCalcOutput(int, const BlockContext& ctx) const {
  ctx.output(0)[0] = bias_ + amplitude_ * std::sin(omega_ * ctx.time() + phase_);
}

}  // namespace mechflow::blocks
