#include "blocks/library/friction_from_normal_force.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace mechflow::blocks {

FrictionFromNormalForceBlock::FrictionFromNormalForceBlock(const std::string& name,
                                                           const mech::FrictionLawParams& law, bool bilateral)
    : Block("friction_from_normal_force", name), law_(law), bilateral_(bilateral) {
  DeclareInputPort("N");
  DeclareInputPort("v");
  DeclareOutputPort("F");
  DeclareOutputPort("sliding");
  SetFeedthrough(1, 1, false);
}

double FrictionFromNormalForceBlock::PressingForce(double normal) const {
  return bilateral_ ? std::abs(normal) : std::max(normal, 0.0);
}

void FrictionFromNormalForceBlock::DoInitialize(const BlockContext&) const {
  largest_pull_ = largest_pull_time_ = largest_size_ = 0.0;
}

void FrictionFromNormalForceBlock::DoCalcOutput(int port, const BlockContext& ctx) const {
  const double normal = ctx.input_scalar(0);
  if (!bilateral_) {
    largest_size_ = std::max(largest_size_, std::abs(normal));
    if (normal < largest_pull_) {
      largest_pull_ = normal;
      largest_pull_time_ = ctx.time();
    }
  }
  const double pressing = PressingForce(normal);
  ctx.output(port)[0] = port == 0 ? mech::FrictionForce(law_, pressing, ctx.input_scalar(1)) : law_.mu_dynamic * pressing;
}

std::string FrictionFromNormalForceBlock::PullingWarning() const {
  if (!(largest_pull_ < -1e-6 * largest_size_)) return {};
  char text[400];
  std::snprintf(text, sizeof text,
                "block '%s' (friction_from_normal_force, normal=\"unilateral\") receives a pulling normal force "
                "(N = %.6g N at t = %.6g s, the largest pull) and gives no dry friction while N < 0. Right for a "
                "contact that lifts off; a guide that holds the body both ways carries mu |N|: set "
                "normal=\"bilateral\"",
                name().c_str(), largest_pull_, largest_pull_time_);
  return text;
}

}  // namespace mechflow::blocks
