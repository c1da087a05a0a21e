#pragma once
// Frictional element (docs/ELEMENTS.md 3.6): dry friction between point A on
// body 1 and point B on body 2, along the line between them, with a stiffness
// and damping that hold it while it sticks -- or on one joint coordinate
// (x = q, v = q'), where the force below acts as a generalized force: a
// friction moment on a rotation, a force on a translation.
//
//   modes: STICK (0), SLIP+ (+1, lengthening), SLIP- (-1)
//   state: the stick deflection delta, integrated from v while stuck (the
//          length's change since sticking began)
//   force on body 2 (positive pushes apart):
//     STICK: -c delta - d v      SLIP+: -F      SLIP-: +F
//   switches (mech/stick_slip.h): the slip rate is v, the holding force
//   c delta + d v, the static limit ratio * F; entering STICK sets delta := 0.
// Entering STICK at v = 0 starts with no spring force, so the element does
// not ring. F = c = d = 0 makes it inactive. Parameters may follow inputs
// (LeafSpring feeds F from a normal force).
//
// Exact stick (`exact_stick`, no c and d): while stuck, the relative motion
// is held by a constraint force -- the holding force H = -force, found from
// the whole mechanism's balance (mech/exact_stick.h) -- instead of a spring
// that must first deflect to carry a load. STICK -> SLIP+/- when +-H rises
// through ratio * F; on entering STICK (and at the start) an H already beyond
// the limit slips at once in its direction, so a reversal costs no stick
// phase and a load applied at once is held or not exactly. It has no state
// and no deflection sensor.
// Sensors: force, length, rate, mode, deflection (spring stick only).

#include "mech/bipolar_force.h"
#include "mech/stick_slip_element.h"

namespace mechflow::mech {

struct FrictionalParameters {
  Parameter friction;     // sliding force F [N], >= 0
  Parameter ratio = 1.2;  // static / dynamic
  Parameter stiffness;    // c at sticking [N/m]
  Parameter damping;      // d at sticking [N s/m]
  bool exact_stick = false;  // hold by a constraint force; c and d unused
};

class FrictionalForce final : public StickSlipElement {
 public:
  FrictionalForce(std::string name, std::string origin, int body1, Vec3 point1, int body2, Vec3 point2,
                  FrictionalParameters parameters);
  FrictionalForce(std::string name, std::string origin, const Dof& dof, FrictionalParameters parameters);
  void Initialize(const ElementContext& ctx, std::span<double> state, std::span<double> modes) const override;
  void Evaluate(const ElementContext& ctx, Loads* loads, std::span<double> state_rate,
                std::span<double> sensors) const override;
  ElementCoordinate Coordinate(const std::string& component) const override;
  std::string LinearisedAs(std::span<const double> modes) const override;
  // Exact stick: a hold beyond the static limit slips in its direction.
  bool UpdateModes(const ElementContext& ctx, std::span<double> state, std::span<double> modes) const override;
  bool StuckExactly(const ElementContext& ctx, int hold) const override;
  // Spring stick only: exact stick's holding force comes from the whole mechanism.
  DerivativeSupport derivative_support() const override {
    return p_.exact_stick ? DerivativeSupport::kNone : DerivativeSupport::kAlongCoordinate;
  }
  void Derivatives(const ElementContext& ctx, double x, double v, ElementDerivatives* d) const override;
  void ApplyStickForce(const ElementContext& ctx, int hold, double f, Loads* loads) const override;
  double StickAcceleration(const ElementContext& ctx, int hold, const DynamicsWorkspace& dyn,
                           std::span<const double> vdot) const override;
  double HoldVelocity(const ElementContext& ctx, int hold) const override;

 private:
  StickSlipHold Hold(const ElementContext& ctx, double mode) const override;
  void OnSwitch(const ElementContext& ctx, double from, double to, std::span<double> state) const override;

  struct Slide {
    double x = 0.0, v = 0.0;
    BipolarGeometry line;  // between the points (not for a joint coordinate)
  };
  Slide Measure(const ElementContext& ctx) const;
  void DeclareInterface();
  void Apply(const Slide& g, double f, Loads* loads, const ElementContext& ctx) const;
  // The force the stuck element exerts against the motion it stops
  // (positive resists lengthening).
  double Holding(const ElementContext& ctx, const Slide& g) const;

  int body1_ = -1, body2_ = -1;
  Vec3 point1_ = Vec3::Zero(), point2_ = Vec3::Zero();
  int q_index_ = -1, v_index_ = -1;  // a joint coordinate, or -1
  FrictionalParameters p_;
};

}  // namespace mechflow::mech
