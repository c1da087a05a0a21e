#pragma once
// The law of a compliant contact point (ELEMENTS.md 5.1, 5.2, 5.4), shared
// by the points-plane and circle-plane contacts: the normal force of a
// penetration, the energy of its spring, and the regularised Coulomb
// friction (the exact stick model is mech/contact_stick.h).

#include <string>

#include "mech/loads.h"

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
  // stick="exact": friction holds a point at rest by a constraint force
  // (mech/contact_stick.h) and is Coulomb's while it slides; v_eps unused.
  bool exact_stick = false;
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
// A number as the contacts' messages print it (%g).
std::string ContactNumber(double v);
// The warning of a contact whose penetration crossed its bound (rising).
std::string PenetrationWarning(const ContactLaw& law);

}  // namespace mechflow::mech
