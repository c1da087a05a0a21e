#include "blocks/library/friction_from_normal_force.h"

#include <algorithm>

namespace mechflow::blocks {

FrictionFromNormalForceBlock::FrictionFromNormalForceBlock(const std::string& name,
                                                           const mech::FrictionLawParams& law)
    : Block("friction_from_normal_force", name), law_(law) {
  DeclareInputPort("N");
  DeclareInputPort("v");
  DeclareOutputPort("F");
  DeclareOutputPort("sliding");
  SetFeedthrough(1, 1, false);
}

void FrictionFromNormalForceBlock::DoCalcOutput(int port, const BlockContext& ctx) const {
  const double normal = ctx.input_scalar(0);
  ctx.output(port)[0] =
      port == 0 ? mech::FrictionForce(law_, normal, ctx.input_scalar(1)) : law_.mu_dynamic * std::max(normal, 0.0);
}

}  // namespace mechflow::blocks
