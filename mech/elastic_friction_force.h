#pragma once
// Elastic-friction element (docs/ELEMENTS.md 3.7): a spring c with a damper d in
// series with a Coulomb slider (a Jenkins element), between point A on body 1
// and point B on body 2 along the line between them.
//
//   state: delta, the deflection of the elastic link [m]
//   tension T = c delta + d delta'; force on body 2 (positive apart) = -T
//   modes:  STICK (0): delta' = v,                   T = c delta + d v
//           SLIP+ (+1): delta' = (F - c delta) / d,   T = +F
//           SLIP- (-1): delta' = (-F - c delta) / d,  T = -F
//   switches (mech/stick_slip.h): the holding force is T, the static limit
//           ratio * F, the slip rate the slider velocity u = v - delta'.
// Unlike the Frictional element it is stiff while sliding too (relaxation
// time d/c) and rings after it sticks. With d = 0 it is the plain Jenkins
// element: while sliding delta = +-F/c is algebraic (delta' = 0, set by a
// reset when sliding begins) and slip ends when v crosses 0. F = c = d = 0
// switches it off. Sensors: force, length, rate, mode, deflection.

#include "mech/frictional_force.h"
#include "mech/stick_slip_element.h"

namespace mechflow::mech {

// How both elastic-friction elements lay out and name their slider's crossings.
inline constexpr StickSlip::Order kSliderOrder = StickSlip::Order::kBreakawayFirst;
inline constexpr StickSlip::Wording kSliderWording{"slider breaks away", "the slider sticks"};

class ElasticFrictionForce final : public StickSlipElement {
 public:
  // Throws InputError for negative constants, or c = d = 0 with F > 0.
  ElasticFrictionForce(std::string name, std::string origin, int body1, Vec3 point1, int body2, Vec3 point2,
                       FrictionalParameters parameters);
  void Initialize(const ElementContext& ctx, std::span<double> state, std::span<double> modes) const override;
  void Evaluate(const ElementContext& ctx, Loads* loads, std::span<double> state_rate,
                std::span<double> sensors) const override;
  ElementCoordinate Coordinate(const std::string& component) const override;
  std::string LinearisedAs(std::span<const double> modes) const override;
  DerivativeSupport derivative_support() const override { return DerivativeSupport::kAlongCoordinate; }
  void Derivatives(const ElementContext& ctx, double x, double v, ElementDerivatives* d) const override;

 private:
  StickSlipHold Hold(const ElementContext& ctx, double mode) const override;
  void OnSwitch(const ElementContext& ctx, double from, double to, std::span<double> state) const override;

  struct Values : BipolarGeometry {
    double delta_rate, tension;
  };
  Values Compute(const ElementContext& ctx, double mode) const;
  // The deflection while sliding when d = 0 (+-F/c); 0 otherwise.
  double SlidingDeflection(const ElementContext& ctx, double mode) const;

  int body1_, body2_;
  Vec3 point1_, point2_;
  FrictionalParameters p_;
};

}  // namespace mechflow::mech
