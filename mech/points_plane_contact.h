#pragma once
// Points-plane contact (ELEMENTS.md 5.1, 5.2, 5.4): points fixed on body 1
// against an unbounded plane fixed on body 2 (a point P0 and the external
// normal N, normalised).
//
//   penetration  delta_i = -(p_i - P0) . N,   rate delta_i' = -w . N
//   normal force N_i = max(0, c delta^n + D(delta) delta')    (never pulls)
//   D(delta) = d                                  when depth = 0
//            = d * STEP(delta; 0 -> depth)        otherwise (no jump at touch)
//   friction F_t = -mu(|w_t|) N_i w_t / sqrt(|w_t|^2 + v_eps^2)
//            (regularised Coulomb: a loaded body creeps at about
//            v_eps tan(theta)/mu), with a static peak that falls to the
//            sliding value over the Stribeck velocity v_s:
//            mu(s) = mu + (mu_static - mu) exp(-(s / v_s)^2)
// w is the velocity of the point relative to the material point of body 2
// under it. Touching and leaving are events: each point has a mode (in
// contact or not) switched when its penetration crosses zero, so the force
// (and a constant damping's jump) never switches inside a step.
// Sensors: normal (sum of N_i), penetration (largest), slip (speed of the
// most loaded point), friction (size of the summed friction force), energy
// (stored in the contact springs of the points in contact).

#include <vector>

#include "mech/force_element.h"

namespace mechflow::mech {

struct ContactLaw {
  double stiffness = 0.0;      // c [N/m^n]
  double exponent = 1.0;       // n >= 1
  double damping = 0.0;        // d, or the maximum of the ramp [N s/m]
  double damping_depth = 0.0;  // penetration over which damping builds up [m]; 0: constant
  double mu = 0.0;             // friction coefficient while sliding
  double mu_static = 0.0;      // at rest, >= mu
  double stribeck_velocity = 1e-3;  // v_s [m/s], > 0
  double v_eps = 1e-4;         // regularisation velocity [m/s]
  // Sanity bound on the penetration [m], > 0: deeper means the contact is
  // too soft or a body passes through; the run warns (once per element, with
  // the time) through an event (ForceElement::CrossingWarning).
  double max_penetration = kDefaultMaxPenetration;
  static constexpr double kDefaultMaxPenetration = 0.05;
};

// The normal and friction loads of one contact point p (global) of body 1
// against body 2 with outward normal n (global, unit) at penetration delta.
struct PointContactLoad {
  double normal = 0.0;
  double slip = 0.0;  // tangential speed
  Vec3 friction = Vec3::Zero();
};
PointContactLoad ApplyPointContact(const Kinematics& kin, const ContactLaw& law, int body1, int body2,
                                   const Vec3& p, const Vec3& n, double delta, Loads* loads);
// The normal force law alone: max(0, c delta^n + D(delta) rate), 0 when delta <= 0.
double ContactNormalForce(const ContactLaw& law, double delta, double rate);
// The energy stored in the contact spring, c delta^(n+1) / (n+1), 0 when delta <= 0.
double ContactEnergy(const ContactLaw& law, double delta);
// Checks a law's numbers; throws InputError starting with `where`.
void CheckContactLaw(const ContactLaw& law, const std::string& where);
// The warning of a contact whose penetration crossed its bound (rising).
std::string PenetrationWarning(const ContactLaw& law);
// How deep the global point p lies beyond the plane of body 2 through
// plane_point with unit external normal `normal` (both in body 2's frame).
double PlaneDepth(const Kinematics& kin, int body2, const Vec3& plane_point, const Vec3& normal, const Vec3& p);
// The load warning of contact `name` whose body 1 starts `depth` into the
// plane of body 2; empty within law.max_penetration (a preloaded rest state).
// When body 1's centre of mass lies beyond the plane too, more of the body is
// inside than out: the normal most likely points into the body it should
// hold, and the warning says so (not for a body 1 fixed to the ground, whose
// centre of mass says nothing).
std::string StartPenetrationWarning(const ElementContext& ctx, const std::string& name, const ContactLaw& law,
                                    double depth, int body1, int body2, const Vec3& plane_point, const Vec3& normal);
// What `mechflow modes` says of a contact linearised with these point modes
// (nonzero: touching).
std::string ContactLinearisedAs(std::span<const double> modes);

class PointsPlaneContact final : public ForceElement {
 public:
  PointsPlaneContact(std::string name, std::string origin, int body1, std::vector<Vec3> points, int body2,
                     Vec3 plane_point, Vec3 normal, ContactLaw law);
  void Initialize(const ElementContext& ctx, std::span<double> state, std::span<double> modes) const override;
  void Evaluate(const ElementContext& ctx, Loads* loads, std::span<double> state_rate,
                std::span<double> sensors) const override;
  ElementCoordinate Coordinate(const std::string& component) const override;
  void ZeroCrossings(const ElementContext& ctx, std::span<double> values) const override;
  void OnCrossing(int index, int direction, const ElementContext& ctx, std::span<double> state,
                  std::span<double> modes) const override;
  // A point exactly on the plane and moving into it is in contact: the solver
  // would not see a crossing that starts at zero.
  bool UpdateModes(const ElementContext& ctx, std::span<double> state, std::span<double> modes) const override;
  // The last crossing is the deepest point passing max_penetration.
  std::string CrossingWarning(int index, int direction) const override;
  // The deepest point starts beyond max_penetration.
  std::string StartWarning(const ElementContext& ctx) const override;
  std::string LinearisedAs(std::span<const double> modes) const override;


 private:
  double Penetration(const ElementContext& ctx, int i, Vec3* p) const;

  int body1_, body2_;
  std::vector<Vec3> points_;
  Vec3 plane_point_, normal_;
  ContactLaw law_;
};

}  // namespace mechflow::mech
