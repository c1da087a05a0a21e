#pragma once
// Joint force (ELEMENTS.md 3.2): a scalar law on one coordinate of a joint;
// x = q, v = q', and a positive value tends to increase q (a force for a
// translation, a torque for a rotation). Sensors: force, length (= q), rate.

#include <memory>

#include "mech/force_law.h"

namespace mechflow::mech {

class JointForce final : public ForceElement {
 public:
  JointForce(std::string name, std::string origin, const Dof& dof, std::unique_ptr<ForceLaw> law);
  void Evaluate(const ElementContext& ctx, Loads* loads, std::span<double> state_rate,
                std::span<double> sensors) const override;
  ElementCoordinate Coordinate(const std::string& component) const override;
  DerivativeSupport derivative_support() const override {
    return law_->has_derivatives() ? DerivativeSupport::kAlongCoordinate : DerivativeSupport::kNone;
  }
  void Derivatives(const ElementContext& ctx, double x, double v, ElementDerivatives* d) const override {
    law_->Derivatives(x, v, ctx, &d->force_x, &d->force_v);
  }

 private:
  int q_index_, v_index_;
  std::unique_ptr<ForceLaw> law_;
};

}  // namespace mechflow::mech
