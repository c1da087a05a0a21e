#include "mech/contact_law.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "mech/errors.h"
#include "mech/kinematics.h"

namespace mechflow::mech {
std::string ContactNumber(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", v);
  return buffer;
}

double ContactNormalForce(const ContactLaw& law, double delta, double rate) {
  if (delta <= 0) return 0.0;
  double damping = law.damping;
  if (law.damping_depth > 0) {
    const double s = std::min(delta / law.damping_depth, 1.0);
    damping *= s * s * (3 - 2 * s);
  }
  // the linear law (exponent 1, the default) without pow: it is evaluated for every point many times a step
  const double spring = law.exponent == 1.0 ? delta : std::pow(delta, law.exponent);
  return std::max(0.0, law.stiffness * spring + damping * rate);
}

double ContactEnergy(const ContactLaw& law, double delta) {
  if (!(delta > 0)) return 0.0;
  return law.exponent == 1.0 ? 0.5 * law.stiffness * delta * delta
                             : law.stiffness * std::pow(delta, law.exponent + 1) / (law.exponent + 1);
}

void CheckContactLaw(const ContactLaw& law, const std::string& where) {
  auto require = [&](bool ok, const char* what, double value) {
    if (!ok) throw InputError(where + what + " (found " + ContactNumber(value) + ")");
  };
  require(law.exponent >= 1.0, "the stiffness exponent must be at least 1", law.exponent);
  require(law.stiffness >= 0, "the stiffness must be >= 0", law.stiffness);
  require(law.damping >= 0, "the damping must be >= 0", law.damping);
  require(law.damping_depth >= 0, "damping_depth must be >= 0", law.damping_depth);
  require(law.mu >= 0, "the friction coefficient mu must be >= 0", law.mu);
  require(law.mu_static >= law.mu, "mu_static must not be below mu (static below dynamic friction)",
          law.mu_static);
  require(law.stribeck_velocity > 0, "stribeck_velocity must be > 0", law.stribeck_velocity);
  require(law.v_eps > 0, "v_eps must be > 0", law.v_eps);
  require(law.max_penetration > 0, "max_penetration must be > 0", law.max_penetration);
}

std::string PenetrationWarning(const ContactLaw& law) {
  return "penetration exceeds max_penetration = " + ContactNumber(law.max_penetration) +
         " m (is the contact too soft, or is a body passing through the plane?)";
}

PointContactLoad ApplyPointContact(const Kinematics& kin, const ContactLaw& law, int body1, int body2,
                                   const Vec3& p, const Vec3& n, double delta, Loads* loads) {
  const Vec3 w = MaterialVelocityAt(kin, body1, p) - MaterialVelocityAt(kin, body2, p);
  PointContactLoad out;
  out.normal = ContactNormalForce(law, std::max(delta, 0.0), -w.dot(n));
  const Vec3 wt = w - w.dot(n) * n;
  out.slip = wt.norm();
  const double stribeck = out.slip / law.stribeck_velocity;
  const double mu = law.mu + (law.mu_static - law.mu) * std::exp(-stribeck * stribeck);
  out.friction = -mu * out.normal * wt / std::sqrt(wt.squaredNorm() + law.v_eps * law.v_eps);
  const Vec3 load = out.normal * n + out.friction;
  loads->AddForce(kin, body1, p, load);
  loads->AddForce(kin, body2, p, -load);
  return out;
}

}  // namespace mechflow::mech
