#pragma once
// Circle-plane contact (ELEMENTS.md 5.3): a circle on body 1 (centre C,
// radius R, circle normal n_c of either sign) against an unbounded plane on
// body 2 (point P0, external normal N). The deepest rim point
//   Q = C + R u,   u = -(N - (N.n_c) n_c) / |N - (N.n_c) n_c|
// carries the contact, with penetration delta = R sqrt(1 - (N.n_c)^2) -
// (C - P0).N and the law of the points-plane contact; body 1's material
// velocity at Q includes w1 x (Q - C), which is how a spinning roller drives
// what it touches. A circle lying flat on the plane (N parallel to n_c) has
// no single deepest point: the evaluation fails with a message.
// Touch and release are events. Sensors: normal, penetration, slip, friction,
// energy (stored in the contact spring).
//
// With law.exact_stick (stick="exact") the friction is that of
// mech/contact_stick.h: a circle at rest at Q is held by two holding
// forces, so it rolls without slip exactly (Q's material velocity stays
// zero while Q itself runs round the rim). Modes [touching | ContactStick's],
// crossings [penetration, max_penetration | ContactStick's], and a sensor
// mode_1 (0 open, 1 stuck, 2 sliding).

#include <optional>

#include "mech/contact_stick.h"
#include "mech/points_plane_contact.h"

namespace mechflow::mech {

class CirclePlaneContact final : public ForceElement {
 public:
  CirclePlaneContact(std::string name, std::string origin, int body1, Vec3 centre, Vec3 circle_normal, double radius,
                     int body2, Vec3 plane_point, Vec3 normal, ContactLaw law);
  void Initialize(const ElementContext& ctx, std::span<double> state, std::span<double> modes) const override;
  void Evaluate(const ElementContext& ctx, Loads* loads, std::span<double> state_rate,
                std::span<double> sensors) const override;
  ElementCoordinate Coordinate(const std::string& component) const override;
  void ZeroCrossings(const ElementContext& ctx, std::span<double> values) const override;
  // Crossing 1 is the penetration passing max_penetration.
  std::string CrossingWarning(int index, int direction) const override;
  // The deepest rim point starts beyond max_penetration.
  std::string StartWarning(const ElementContext& ctx) const override;
  std::string LinearisedAs(std::span<const double> modes) const override;
  void OnCrossing(int index, int direction, const ElementContext& ctx, std::span<double> state,
                  std::span<double> modes) const override;
  // At rest, touching exactly when it penetrates.
  bool ModesAtRest(const ElementContext& ctx, std::span<double> state, std::span<double> modes) const override;
  // Exact stick: after an event, a hold beyond its cone slides, a reversed slip sticks.
  bool UpdateModes(const ElementContext& ctx, std::span<double> state, std::span<double> modes) const override;
  std::string CrossingName(int index, int direction) const override;

  // Exact stick (law.exact_stick): holds 0 and 1 are Q's tangential slips.
  bool StuckExactly(const ElementContext& ctx, int hold) const override;
  void ApplyStickForce(const ElementContext& ctx, int hold, double f, Loads* loads) const override;
  double StickAcceleration(const ElementContext& ctx, int hold, const DynamicsWorkspace& dyn,
                           std::span<const double> vdot) const override;
  double HoldVelocity(const ElementContext& ctx, int hold) const override;
  std::string HoldName(int hold) const override;
  bool UnholdableIsError() const override { return true; }
  void FollowSlip(const ElementContext& ctx, std::span<double> modes) const override;

 private:
  // Penetration, deepest point Q and the plane normal (global); with
  // q_rate, also Q's velocity as it runs round the rim.
  double Geometry(const ElementContext& ctx, Vec3* q, Vec3* n, Vec3* q_rate = nullptr) const;
  // Q as the stick model sees it; the penetration into *delta.
  ContactPointMotion Motion(const ElementContext& ctx, double* delta) const;
  double NormalForce(const ContactPointMotion& m, double delta) const {
    return ContactNormalForce(law_, std::max(delta, 0.0), -m.slip.dot(m.normal));
  }
  static std::span<double> StickModes(std::span<double> modes) { return modes.subspan(1); }
  static std::span<const double> StickModes(std::span<const double> modes) { return modes.subspan(1); }

  int body1_, body2_;
  Vec3 centre_, circle_normal_;
  double radius_;
  Vec3 plane_point_, normal_;
  Vec3 tangent1_, tangent2_;  // body 2's frame
  ContactLaw law_;
  std::optional<ContactStick> stick_;  // with law.exact_stick
};

}  // namespace mechflow::mech
