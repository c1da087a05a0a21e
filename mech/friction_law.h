#pragma once
// Regularised dry friction with a Stribeck drop and a viscous term.
//
// The friction force opposing a sliding velocity v [m/s] under a normal force
// N [N] is
//
//   mu(v) = mu_d + (mu_s - mu_d) * exp(-(|v| / v_s)^2)
//   F(N, v) = -( mu(v) * max(N, 0) * tanh(v / v_reg) + c_visc * v )
//
// * max(N, 0): a normal force that pulls (N < 0) means the surfaces are apart,
//   so there is no dry friction (no adhesion).
// * tanh(v / v_reg) replaces sign(v): the force is smooth, which a stiff
//   integrator needs, at the price of creep: a body held by a tangential load
//   F_t < mu_s N slides at about v_reg * atanh(F_t / (mu_s N)).
// * the largest force reachable at small |v| is close to mu_s N when
//   v_reg << v_s, so breakaway happens at the static friction level.
// Used by the friction-from-normal-force block (the contacts write their own
// Stribeck curve, regularised by |w_t| rather than tanh).

namespace mechflow::mech {

struct FrictionLawParams {
  double mu_static = 0.5;          // [-]
  double mu_dynamic = 0.5;         // [-]
  double stribeck_velocity = 1e-2; // v_s [m/s], > 0
  double viscous = 0.0;            // c_visc [N s/m], >= 0
  double regularisation_velocity = 1e-4;  // v_reg [m/s], > 0
};

// Friction coefficient mu(v) of the Stribeck curve (no regularisation).
double StribeckCoefficient(const FrictionLawParams& p, double v);

// Friction force F(N, v) [N] as documented above; opposes v.
double FrictionForce(const FrictionLawParams& p, double normal_force, double v);

// Empty when the parameters are usable, otherwise what is wrong with them.
const char* CheckFrictionLawParams(const FrictionLawParams& p);

}  // namespace mechflow::mech
