#pragma once
// Applied force and torque on a body: components are Parameters (constants
// or functions of the mechanism's inputs, e.g. a controller's output), in
// global axes or in the body's axes (`body_axes`). The force acts at `point`
// (body frame); the torque is a pure moment. Sensors: fx fy fz mx my mz, as
// given (in the axes chosen), always all six.

#include <array>

#include "mech/force_element.h"

namespace mechflow::mech {

class AppliedForce final : public ForceElement {
 public:
  AppliedForce(std::string name, std::string origin, int body, Vec3 point, std::array<Parameter, 3> force,
               std::array<Parameter, 3> torque, bool body_axes);
  void Evaluate(const ElementContext& ctx, Loads* loads, std::span<double> state_rate,
                std::span<double> sensors) const override;
  DerivativeSupport derivative_support() const override { return DerivativeSupport::kStateIndependent; }

 private:
  int body_;
  Vec3 point_;
  std::array<Parameter, 3> force_, torque_;
  bool body_axes_;
};

}  // namespace mechflow::mech
