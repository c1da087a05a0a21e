#pragma once
// Bipolar force (ELEMENTS.md 3.1): a scalar law acting along the line between
// point A on body 1 and point B on body 2. x = |p_B - p_A|, v = dx/dt; a
// positive F pushes the points apart: +F u on body 2 at p_B, -F u on body 1 at
// p_A, u = (p_B - p_A)/x. At zero length the direction is undefined: a zero
// force is accepted, any other force fails the evaluation (SimulationError).
// Sensors: force, length, rate.

#include <memory>

#include "mech/force_law.h"

namespace mechflow::mech {

class BipolarForce final : public ForceElement {
 public:
  BipolarForce(std::string name, std::string origin, int body1, Vec3 point1, int body2, Vec3 point2,
               std::unique_ptr<ForceLaw> law);
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
  int body1_, body2_;
  Vec3 point1_, point2_;
  std::unique_ptr<ForceLaw> law_;
};

// Length of the element in the configuration `kin` (for a default free length).
double BipolarLength(const Kinematics& kin, int body1, const Vec3& point1, int body2, const Vec3& point2);

// The line of a bipolar element (also the friction elements'): its ends pa
// (body 1) and pb (body 2), length x, unit direction u from pa to pb (zero at
// zero length) and rate of lengthening v.
struct BipolarGeometry {
  Vec3 pa, pb, u;
  double x = 0.0, v = 0.0;
};
BipolarGeometry MeasureBipolar(const Kinematics& kin, int body1, const Vec3& point1, int body2, const Vec3& point2);

}  // namespace mechflow::mech
