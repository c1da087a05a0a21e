#pragma once
// Elastic-friction-2 element (docs/ELEMENTS.md 3.8): a spring c1 in series with a
// block made of a Coulomb slider in parallel with a spring c2, between point
// A on body 1 and point B on body 2 along the line between them. It has no
// dashpot, so its hysteresis loops do not depend on the rate.
//
//   x' = x - L0; x2 = deflection of the parallel block (state)
//   tension T = c1 (x' - x2); force on body 2 (positive apart) = -T
//   slider force T_s = T - c2 x2; friction limit mu N (mu0 N to break away):
//     transmitted (default): N = |T|      (loops scale with the amplitude)
//     spring (law b):         N = |c2 x2|
//     constant (law c):       N = F_N, an expression
//   modes: STICK (0): x2 held (x2' = 0)
//          SLIP s = +-1: x2 is the algebraic solution of T_s = s mu N, which
//          moves with the sign of v (mu < 1 for the default law)
//   switches (mech/stick_slip.h): the holding force is T_s, the static
//           limit mu0 N, the slip rate v. Breaking away, x2 jumps to the
//           sliding solution when mu0 > mu (a reset map); sticking, x2 is
//           reset to the sliding solution, so what the state drifted is dropped.
// While sliding the state follows the sliding solution through its rate
// (x2' = dx2/dx' v; law c ignores a time-varying F_N there) but the forces
// use the algebraic value. Sensors: force, length, rate, mode, deflection.

#include "mech/bipolar_force.h"
#include "mech/stick_slip_element.h"

namespace mechflow::mech {

enum class FrictionLimit { kTransmitted, kSpring, kConstant };

struct ElasticFriction2Parameters {
  Parameter series_stiffness;    // c1 [N/m], > 0
  Parameter parallel_stiffness;  // c2 [N/m], >= 0
  Parameter mu;                  // dynamic coefficient, >= 0
  Parameter mu0;                 // static coefficient, >= mu
  Parameter free_length;         // L0 [m]
  FrictionLimit limit = FrictionLimit::kTransmitted;
  Parameter normal_force;  // F_N [N] of the constant limit
};

class ElasticFriction2Force final : public StickSlipElement {
 public:
  // Throws InputError for constants out of range: a negative stiffness or
  // coefficient, mu0 < mu, or a mu for which sliding has no solution.
  ElasticFriction2Force(std::string name, std::string origin, int body1, Vec3 point1, int body2, Vec3 point2,
                        ElasticFriction2Parameters parameters);
  void Initialize(const ElementContext& ctx, std::span<double> state, std::span<double> modes) const override;
  void Evaluate(const ElementContext& ctx, Loads* loads, std::span<double> state_rate,
                std::span<double> sensors) const override;
  ElementCoordinate Coordinate(const std::string& component) const override;
  std::string LinearisedAs(std::span<const double> modes) const override;
  // A slip against the velocity (a break-away found where the slider force
  // only grazes its limit at a turning point, as in a stuck oscillation that
  // started at the limit) sticks again, holding x2.
  bool UpdateModes(const ElementContext& ctx, std::span<double> state, std::span<double> modes) const override;

 private:
  StickSlipHold Hold(const ElementContext& ctx, double mode) const override;
  void OnSwitch(const ElementContext& ctx, double from, double to, std::span<double> state) const override;

  struct Values : BipolarGeometry {
    double x2, x2_rate, tension, slider_force, limit_force;  // limit_force = N
  };
  Values Compute(const ElementContext& ctx, double mode) const;

  int body1_, body2_;
  Vec3 point1_, point2_;
  ElasticFriction2Parameters p_;
};

}  // namespace mechflow::mech
