#include "mech/elastic_friction2_force.h"

#include <cmath>
#include <string>

#include "mech/elastic_friction_force.h"
#include "mech/errors.h"

namespace mechflow::mech {
namespace {

double Sign(double x) { return x < 0 ? -1.0 : 1.0; }

}  // namespace

ElasticFriction2Force::ElasticFriction2Force(std::string name, std::string origin, int body1, Vec3 point1, int body2,
                                             Vec3 point2, ElasticFriction2Parameters parameters)
    : StickSlipElement(std::move(name), std::move(origin), kSliderOrder, kSliderWording),
      body1_(body1),
      body2_(body2),
      point1_(point1),
      point2_(point2),
      p_(parameters) {
  DeclareDependsOnInputs(p_.series_stiffness.uses_inputs || p_.parallel_stiffness.uses_inputs ||
                         p_.mu.uses_inputs || p_.mu0.uses_inputs || p_.free_length.uses_inputs ||
                         p_.normal_force.uses_inputs);
  const std::string what = this->origin() + (this->origin().empty() ? "" : ": ") +
                           "elastic-friction-2 element '" + this->name() + "'";
  auto fail_if = [&](const Parameter& p, bool bad, const std::string& message) {
    if (p.is_constant() && bad) throw InputError(what + ": " + message);
  };
  const Parameter &c1 = p_.series_stiffness, &c2 = p_.parallel_stiffness, &mu = p_.mu, &mu0 = p_.mu0;
  fail_if(c1, c1.value <= 0.0, "the series stiffness c1 must be positive");
  fail_if(c2, c2.value < 0.0, "the parallel stiffness c2 must not be negative");
  fail_if(mu, mu.value < 0.0, "the friction coefficient mu must not be negative");
  fail_if(mu0, mu0.value < 0.0, "the static friction coefficient mu0 must not be negative");
  if (mu.is_constant() && mu0.is_constant() && mu0.value < mu.value)
    throw InputError(what + ": the static coefficient mu0 must not be below the dynamic mu");
  // Sliding needs a positive denominator in the algebraic x2 (see Compute).
  if (p_.limit == FrictionLimit::kTransmitted)
    fail_if(mu, mu.value >= 1.0, "mu must be below 1 when the limit follows the transmitted force");
  if (p_.limit == FrictionLimit::kSpring && c1.is_constant() && c2.is_constant())
    fail_if(mu, mu.value * c2.value >= c1.value + c2.value, "mu c2 must be below c1 + c2 for the spring limit");
  if (p_.limit == FrictionLimit::kConstant)
    fail_if(p_.normal_force, p_.normal_force.value < 0.0, "the normal force must not be negative");
  DeclareBodies({body1_, body2_});  // its footprint in the sparse Jacobian
  for (const char* s : {"force", "length", "rate", "mode", "deflection"}) DeclareSensor(s);
  if (c1.is_constant() && c2.is_constant()) DeclareSensor("energy");  // of both springs
  DeclareStates(1);  // x2
  DeclareStickSlip();
}

ElasticFriction2Force::Values ElasticFriction2Force::Compute(const ElementContext& ctx, double mode) const {
  Values r;
  static_cast<BipolarGeometry&>(r) = MeasureBipolar(*ctx.kin, body1_, point1_, body2_, point2_);
  const double xp = r.x - p_.free_length.Get(ctx);
  const double c1 = p_.series_stiffness.Get(ctx), c2 = p_.parallel_stiffness.Get(ctx), mu = p_.mu.Get(ctx);
  if (mode == kStick) {
    r.x2 = ctx.state[0];
    r.x2_rate = 0.0;
  } else {
    // T_s = s mu N solved for x2; every law is linear in x' on each side of
    // x' = 0 (T and x2 have the sign of x' there), so x2 = ratio x' + shift.
    double ratio = 0.0, shift = 0.0;
    switch (p_.limit) {
      case FrictionLimit::kTransmitted: {
        const double k = c1 * (1.0 - mode * Sign(xp) * mu);
        ratio = k / (c2 + k);
        break;
      }
      case FrictionLimit::kSpring:
        ratio = c1 / (c1 + c2 + mode * Sign(xp) * mu * c2);
        break;
      case FrictionLimit::kConstant:
        ratio = c1 / (c1 + c2);
        shift = -mode * mu * p_.normal_force.Get(ctx) / (c1 + c2);
        break;
    }
    if (!(ratio > 0.0) || !(ratio <= 1.0))
      throw SimulationError(origin() + ": elastic-friction-2 element '" + name() +
                            "': sliding has no solution with these stiffnesses and mu (dx2/dx' = " +
                            std::to_string(ratio) + ")");
    r.x2 = ratio * xp + shift;
    r.x2_rate = ratio * r.v;
  }
  r.tension = c1 * (xp - r.x2);
  r.slider_force = r.tension - c2 * r.x2;
  switch (p_.limit) {
    case FrictionLimit::kTransmitted: r.limit_force = std::abs(r.tension); break;
    case FrictionLimit::kSpring: r.limit_force = std::abs(c2 * r.x2); break;
    case FrictionLimit::kConstant: r.limit_force = p_.normal_force.Get(ctx); break;
  }
  return r;
}

void ElasticFriction2Force::Initialize(const ElementContext& ctx, std::span<double> state,
                                       std::span<double> modes) const {
  state[0] = 0.0;
  const Values r = Compute(ctx, kStick);
  modes[0] = StickSlip::InitialMode(r.v);
  if (modes[0] != kStick) state[0] = Compute(ctx, modes[0]).x2;
}

void ElasticFriction2Force::Evaluate(const ElementContext& ctx, Loads* loads, std::span<double> state_rate,
                                     std::span<double> sensors) const {
  const Values r = Compute(ctx, ctx.modes[0]);
  loads->AddForce(*ctx.kin, body2_, r.pb, -r.tension * r.u);
  loads->AddForce(*ctx.kin, body1_, r.pa, r.tension * r.u);
  state_rate[0] = r.x2_rate;
  sensors[0] = -r.tension;
  sensors[1] = r.x;
  sensors[2] = r.v;
  sensors[3] = ctx.modes[0];
  sensors[4] = r.x2;
  if (stores_energy()) {
    const double c1 = p_.series_stiffness.value, c2 = p_.parallel_stiffness.value;
    sensors[5] = 0.5 * r.tension * r.tension / c1 + 0.5 * c2 * r.x2 * r.x2;
  }
}

StickSlipHold ElasticFriction2Force::Hold(const ElementContext& ctx, double mode) const {
  const Values r = Compute(ctx, mode);
  return {.slip_rate = r.v, .holding = r.slider_force, .static_limit = p_.mu0.Get(ctx) * r.limit_force};
}

void ElasticFriction2Force::OnSwitch(const ElementContext& ctx, double from, double to,
                                     std::span<double> state) const {
  // Sticking holds the sliding solution reached; breaking away jumps to the
  // sliding solution of the new direction (a jump when mu0 > mu).
  state[0] = Compute(ctx, to == kStick ? from : to).x2;
}

bool ElasticFriction2Force::UpdateModes(const ElementContext& ctx, std::span<double> state,
                                        std::span<double> modes) const {
  return StickWhereSlipReverses(ctx, state, modes);
}

ElementCoordinate ElasticFriction2Force::Coordinate(const std::string& component) const {
  return component.empty() ? ElementCoordinate::Line(body1_, point1_, body2_, point2_) : ElementCoordinate{};
}

std::string ElasticFriction2Force::LinearisedAs(std::span<const double> modes) const {
  if (modes[0] == 0.0) return "stuck: c1 in series with c2 enters the modes (the slider held)";
  return StickSlip::Sliding(modes[0]) +
         ": the slider moves on its sliding solution, so the stiffness seen is not that of c1 with c2 held";
}

}  // namespace mechflow::mech
