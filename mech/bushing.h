#pragma once
// Bushing (ELEMENTS.md 4): six-component linear stiffness and damping between
// point P1 on body 1 and point P2 on body 2, in the axes of body 1.
//   delta  = A1^T (p2 - p1),  delta' = A1^T (v_P2 - v_P1) - (A1^T w1) x delta
//   theta  = vee(R - R^T)/2 with R = A1^T A2 (A1^T A2)_0^T   (small angles)
//   w_rel  = A1^T (w2 - w1)
//   f = -(C delta + D delta') + preload,  m = -(Ca theta + Da w_rel) + preload
// f and m are the load ON BODY 2 (body-1 axes; ELEMENTS' f and m with the
// sign turned, plus the preloads): A1 f acts on body 2 at p2 and A1 m on body
// 2; -A1 f and -A1 m act on body 1.
//
// Where body 1's force acts: ELEMENTS.md 4 puts -A1 f at P1. We apply it at
// the material point of body 1 that is at p2 now (not at P1): the two wrenches
// are then equal and opposite about every point (at P1 they differ by the
// moment delta x f, non-zero for unequal stiffnesses), and the stiffness
// force is exactly minus the gradient of (1/2) delta^T C delta, so an
// undamped bushing between two moving bodies conserves energy. The two
// readings agree when body 1 is the ground (BU-1) and to first order in delta.
//
// The initial relative rotation (A1^T A2)_0 is taken from `initial`, the
// kinematics of the initial configuration (UpdateKinematics at the initial
// coordinates, computed by the caller), and stored. P2 is the
// caller's: the loader's auto-detection passes the point of body 2 that
// coincides with P1 in that configuration (BushingCoincidentPoint).
// Sensors: fx fy fz mx my mz (f, m: on body 2, body-1 axes), dx dy dz
// (delta), ax ay az (theta).

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
  ElementCoordinate Coordinate(const std::string& component) const override;

 private:
  int body1_, body2_;
  Vec3 point1_, point2_;
  BushingParameters p_;
  Mat3 initial_relative_;  // (A1^T A2) at the initial configuration
};

// The point of body 2 (in its frame) that coincides with `point1` of body 1 in
// the configuration `kin`.
Vec3 BushingCoincidentPoint(const Kinematics& kin, int body1, const Vec3& point1, int body2);

}  // namespace mechflow::mech
