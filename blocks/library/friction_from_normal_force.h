#pragma once
// Friction from a normal force: F = friction force for normal force N and
// sliding velocity v, by the regularised Stribeck law of mech/friction_law.h:
//
//   mu(v) = mu_d + (mu_s - mu_d) exp(-(|v| / v_s)^2)
//   F     = -( mu(v) max(N, 0) tanh(v / v_reg) + c_visc v )
//
//   ports:   inputs N (normal force [N]; a pulling N < 0 gives no dry
//            friction) and v (sliding velocity [m/s]); outputs F (friction
//            force [N], opposing v; both inputs feed it directly) and
//            sliding = mu_d max(N, 0) (the size of the sliding friction, for
//            a friction element with stick/slip memory, whose own modes
//            decide its direction and sticking; fed by N only); all width 1
//   params:  mu_static mu_s, mu_dynamic mu_d (required, >= 0),
//            stribeck_velocity v_s [m/s] (0.01, > 0), viscous c_visc [N s/m]
//            (0, >= 0), regularisation_velocity v_reg [m/s] (1e-4, > 0)
// The tanh regularisation makes F smooth (no events, no modes), at the price
// of creep: a held load below mu_s N slides at about v_reg atanh(F / (mu_s N)).

#include "blocks/block.h"
#include "mech/friction_law.h"

namespace mechflow::blocks {

class FrictionFromNormalForceBlock : public Block {
 public:
  FrictionFromNormalForceBlock(const std::string& name, const mech::FrictionLawParams& law);
  const mech::FrictionLawParams& law() const { return law_; }

 protected:
  void DoCalcOutput(int port, const BlockContext& ctx) const override;

 private:
  mech::FrictionLawParams law_;
};

}  // namespace mechflow::blocks
