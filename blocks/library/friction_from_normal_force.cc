#include "blocks/library/friction_from_normal_force.h"

namespace mechflow::blocks {

FrictionFromNormalForceBlock::FrictionFromNormalForceBlock(const std::string& name,
                                                           const mech::FrictionLawParams& law)
    : Block("friction_from_normal_force", name), law_(law) {
  DeclareInputPort("N");
  DeclareInputPort("v");
  DeclareOutputPort("F");
}

void FrictionFromNormalForceBlock::DoCalcOutput(int, const BlockContext& ctx) const {
  ctx.output(0)[0] = mech::FrictionForce(law_, ctx.input_scalar(0), ctx.input_scalar(1));
}

}  // namespace mechflow::blocks
