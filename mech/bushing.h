#pragma once
// Bushing (ELEMENTS.md 4): six-component linear stiffness and damping between
// point P1 on body 1 and point P2 on body 2, in the axes of body 1.
//   delta  = A1^T (p2 - p1),  delta' = A1^T (v_P2 - v_P1) - (A1^T w1) x delta
//   theta  = vee(R - R^T)/2 with R = A1^T A2 (A1^T A2)_0^T   (small angles)
//   f = -(C delta + D delta') + preload,  m = -(Ca theta + Da w_rel) + preload
// f and m (body-1 axes) act on body 2 at P2; their opposites on body 1 at P1.
// The initial relative rotation is taken from the configuration passed to the
// constructor (the assembled initial state). Sensors: fx fy fz mx my mz (on
// body 2, body-1 axes), dx dy dz ax ay az.

#include <array>

#include "mech/force_element.h"

namespace mechflow::mech {

struct BushingParameters {
  std::array<double, 3> stiffness{}, damping{}, angular_stiffness{}, angular_damping{};
  Vec3 preload_force = Vec3::Zero(), preload_moment = Vec3::Zero();
};

class Bushing final : public ForceElement {
 public:
  Bushing(std::string name, std::string origin, int body1, Vec3 point1, int body2, Vec3 point2,
          BushingParameters parameters, const Kinematics& initial);
  void Evaluate(const ElementContext& ctx, Loads* loads, std::span<double> state_rate,
                std::span<double> sensors) const override;

 private:
  int body1_, body2_;
  Vec3 point1_, point2_;
  BushingParameters p_;
  Mat3 initial_relative_;  // (A1^T A2) at the initial configuration
};

}  // namespace mechflow::mech
