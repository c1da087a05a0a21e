#pragma once
// Friction from a normal force: F = friction force for normal force N and
// sliding velocity v, by the regularised Stribeck law of mech/friction_law.h:
//
//   mu(v) = mu_d + (mu_s - mu_d) exp(-(|v| / v_s)^2)
//   F     = -( mu(v) n(N) tanh(v / v_reg) + c_visc v )
//   n(N)  = max(N, 0)  normal="unilateral" (default): a contact that can
//                      only push; a pulling N < 0 means it lifted off
//         = |N|        normal="bilateral": a guide that holds the body both
//                      ways (a slot, a rail), pressed whichever way N acts
//
//   ports:   inputs N (normal force [N]) and v (sliding velocity [m/s]);
//            outputs F (friction force [N], opposing v; both inputs feed
//            it directly) and sliding = mu_d n(N) (the size of the sliding
//            friction, for a friction element with stick/slip memory, whose
//            own modes decide its direction and sticking; fed by N only);
//            all width 1
//   params:  normal ("unilateral" or "bilateral"), mu_static mu_s,
//            mu_dynamic mu_d (required, >= 0),
//            stribeck_velocity v_s [m/s] (0.01, > 0), viscous c_visc [N s/m]
//            (0, >= 0), regularisation_velocity v_reg [m/s] (1e-4, > 0)
// The tanh regularisation makes F smooth (no events, no modes), at the price
// of creep: a held load below mu_s N slides at about v_reg atanh(F / (mu_s N)).
//
// A unilateral block fed a pulling N gives no friction, which is right for a
// contact that lifted off and wrong for a guide (a lever's pivot slot fed its
// reaction): each run keeps the largest pull the block computed with and
// when (in its Context), and PullingWarning() says so after the run, once. A pull below 1e-6 of the
// largest |N| is rounding about a zero (an abs block switching sign within a
// step), not a pull.

#include <memory>
#include <string>

#include "blocks/framework/block.h"
#include "mech/friction_law.h"

namespace mechflow::blocks {

class FrictionFromNormalForceBlock : public Block {
 public:
  FrictionFromNormalForceBlock(const std::string& name, const mech::FrictionLawParams& law, bool bilateral);
  const mech::FrictionLawParams& law() const { return law_; }
  bool bilateral() const { return bilateral_; }
  // The normal force the friction is proportional to: max(N, 0) or |N|.
  double PressingForce(double normal) const;
  // After the run that `run` holds (`block`: this block's index in the
  // diagram): "" when a unilateral block never computed with a pulling N,
  // otherwise a sentence with the largest pull and when it was.
  std::string PullingWarning(const Context& run, int block) const;
  std::unique_ptr<BlockScratch> MakeScratch() const override;

 protected:
  void DoInitialize(const BlockContext& ctx) const override;
  void DoCalcOutput(int port, const BlockContext& ctx) const override;

 private:
  struct Scratch;  // the run's largest pull

  mech::FrictionLawParams law_;
  bool bilateral_ = false;
};

}  // namespace mechflow::blocks
