#include "mech/friction_law.h"

#include <algorithm>
#include <cmath>

namespace mechflow::mech {

double StribeckCoefficient(const FrictionLawParams& p, double v) {
  const double r = v / p.stribeck_velocity;
  return p.mu_dynamic + (p.mu_static - p.mu_dynamic) * std::exp(-r * r);
}

double FrictionForce(const FrictionLawParams& p, double normal_force, double v) {
  const double n = std::max(normal_force, 0.0);
  return -(StribeckCoefficient(p, v) * n * std::tanh(v / p.regularisation_velocity) +
           p.viscous * v);
}

const char* CheckFrictionLawParams(const FrictionLawParams& p) {
  if (!(p.mu_static >= 0.0)) return "mu_static must be >= 0";
  if (!(p.mu_dynamic >= 0.0)) return "mu_dynamic must be >= 0";
  if (p.mu_static < p.mu_dynamic) return "mu_static must not be below mu_dynamic (static below dynamic friction)";
  if (!(p.stribeck_velocity > 0.0)) return "stribeck_velocity must be > 0";
  if (!(p.viscous >= 0.0)) return "viscous must be >= 0";
  if (!(p.regularisation_velocity > 0.0)) return "regularisation_velocity must be > 0";
  return "";
}

}  // namespace mechflow::mech
