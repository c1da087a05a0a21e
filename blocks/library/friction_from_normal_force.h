#pragma once
// Friction from a normal force: F = friction force for normal force N and
// sliding velocity v, by the regularised Stribeck law of mech/friction_law.h:
//
//   mu(v) = mu_d + (mu_s - mu_d) exp(-(|v| / v_s)^2)
//   F     = -( mu(v) max(N, 0) tanh(v / v_reg) + c_visc v )
//
//   inputs:  N [N] (a pulling N < 0 gives no dry friction), v [m/s]
//   output:  F [N], opposing v; both inputs feed it directly
//   params:  mu_static, mu_dynamic, stribeck_velocity v_s [m/s],
//            viscous c_visc [N s/m], regularisation_velocity v_reg [m/s]
// A held load below mu_s N creeps at about v_reg atanh(F / (mu_s N)).

#include "blocks/block.h"
#include "mech/friction_law.h"

namespace mechflow::blocks {

class FrictionFromNormalForceBlock : public Block {
 public:
  FrictionFromNormalForceBlock(const std::string& name, const mech::FrictionLawParams& law);

 protected:
  void DoCalcOutput(int port, const BlockContext& ctx) const override;

 private:
  mech::FrictionLawParams law_;
};

}  // namespace mechflow::blocks
