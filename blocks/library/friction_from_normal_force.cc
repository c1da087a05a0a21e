#include "blocks/library/friction_from_normal_force.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace mechflow::blocks {

// The run's largest pull (most negative N) and when, and the largest |N|.
struct FrictionFromNormalForceBlock::Scratch final : BlockScratch {
  double largest_pull = 0.0, largest_pull_time = 0.0, largest_size = 0.0;
};

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

std::unique_ptr<BlockScratch> FrictionFromNormalForceBlock::MakeScratch() const {
  return std::make_unique<Scratch>();
}

void FrictionFromNormalForceBlock::DoInitialize(const BlockContext& ctx) const { ctx.scratch<Scratch>() = Scratch(); }

void FrictionFromNormalForceBlock::DoCalcOutput(int port, const BlockContext& ctx) const {
  const double normal = ctx.input_scalar(0);
  if (!bilateral_) {
    Scratch& s = ctx.scratch<Scratch>();
    s.largest_size = std::max(s.largest_size, std::abs(normal));
    if (normal < s.largest_pull) {
      s.largest_pull = normal;
      s.largest_pull_time = ctx.time();
    }
  }
  const double pressing = PressingForce(normal);
  ctx.output(port)[0] = port == 0 ? mech::FrictionForce(law_, pressing, ctx.input_scalar(1)) : law_.mu_dynamic * pressing;
}

std::string FrictionFromNormalForceBlock::PullingWarning(const Context& run, int block) const {
  const Scratch* s = RunScratch<Scratch>(run, block);
  if (!s || !(s->largest_pull < -1e-6 * s->largest_size)) return {};
  char text[400];
  std::snprintf(text, sizeof text,
                "block '%s' (friction_from_normal_force, normal=\"unilateral\") receives a pulling normal force "
                "(N = %.6g N at t = %.6g s, the largest pull) and gives no dry friction while N < 0. Right for a "
                "contact that lifts off; a guide that holds the body both ways carries mu |N|: set "
                "normal=\"bilateral\"",
                name().c_str(), s->largest_pull, s->largest_pull_time);
  return text;
}

}  // namespace mechflow::blocks
