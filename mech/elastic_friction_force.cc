#include "mech/elastic_friction_force.h"

#include "mech/errors.h"

namespace mechflow::mech {

ElasticFrictionForce::ElasticFrictionForce(std::string name, std::string origin, int body1, Vec3 point1, int body2,
                                           Vec3 point2, FrictionalParameters parameters)
    : StickSlipElement(std::move(name), std::move(origin), kSliderOrder, kSliderWording),
      body1_(body1),
      body2_(body2),
      point1_(point1),
      point2_(point2),
      p_(parameters) {
  DeclareDependsOnInputs(p_.friction.uses_inputs || p_.ratio.uses_inputs || p_.stiffness.uses_inputs ||
                         p_.damping.uses_inputs);
  // d = 0 is the plain Jenkins element (the deflection is algebraic while
  // sliding, delta = +-F/c), which needs c; only F = c = d = 0 (switched off)
  // may have neither.
  const auto zero = [](const Parameter& p) { return p.is_constant() && p.value == 0.0; };
  const auto negative = [](const Parameter& p) { return p.is_constant() && p.value < 0.0; };
  const std::string what = this->origin() + (this->origin().empty() ? "" : ": ") + "elastic-friction element '" +
                           this->name() + "'";
  if (negative(p_.damping) || negative(p_.stiffness) || negative(p_.friction))
    throw InputError(what + ": friction F, stiffness c and damping d must not be negative");
  if (zero(p_.damping) && zero(p_.stiffness) && !zero(p_.friction))
    throw InputError(what + " needs a positive stiffness c when d = 0 (the deflection while sliding is F/c)");
  DeclareBodies({body1_, body2_});  // its footprint in the sparse Jacobian
  for (const char* s : {"force", "length", "rate", "mode", "deflection"}) DeclareSensor(s);
  if (p_.stiffness.is_constant()) DeclareSensor("energy");  // of the elastic link
  DeclareStates(1);
  DeclareStickSlip();
}

ElasticFrictionForce::Values ElasticFrictionForce::Compute(const ElementContext& ctx, double mode) const {
  Values r;
  static_cast<BipolarGeometry&>(r) = MeasureBipolar(*ctx.kin, body1_, point1_, body2_, point2_);
  const double delta = ctx.state[0];
  const double c = p_.stiffness.Get(ctx), damping = p_.damping.Get(ctx), f = p_.friction.Get(ctx);
  if (c <= 0.0 && damping <= 0.0) {  // switched off: no link, nothing deflects
    r.delta_rate = 0.0;
    r.tension = 0.0;
  } else if (mode == 0.0) {
    r.delta_rate = r.v;
    r.tension = c * delta + damping * r.v;
  } else if (damping <= 0.0) {  // d = 0: delta = +-F/c, set when sliding began
    r.tension = mode * f;
    r.delta_rate = 0.0;
  } else {
    r.tension = mode * f;
    r.delta_rate = (r.tension - c * delta) / damping;
  }
  return r;
}

void ElasticFrictionForce::Initialize(const ElementContext& ctx, std::span<double> state,
                                      std::span<double> modes) const {
  state[0] = 0.0;
  const double v = Compute(ctx, 0.0).v;
  modes[0] = StickSlip::InitialMode(v);
  state[0] = SlidingDeflection(ctx, modes[0]);
}

void ElasticFrictionForce::Evaluate(const ElementContext& ctx, Loads* loads, std::span<double> state_rate,
                                    std::span<double> sensors) const {
  const Values r = Compute(ctx, ctx.modes[0]);
  loads->AddForce(*ctx.kin, body2_, r.pb, -r.tension * r.u);
  loads->AddForce(*ctx.kin, body1_, r.pa, r.tension * r.u);
  state_rate[0] = r.delta_rate;
  sensors[0] = -r.tension;
  sensors[1] = r.x;
  sensors[2] = r.v;
  sensors[3] = ctx.modes[0];
  sensors[4] = ctx.state[0];
  if (p_.stiffness.is_constant()) sensors[5] = 0.5 * p_.stiffness.value * ctx.state[0] * ctx.state[0];
}

void ElasticFrictionForce::Derivatives(const ElementContext& ctx, double, double, ElementDerivatives* d) const {
  // the branches of Compute: force -T, delta' as there
  const double c = p_.stiffness.Get(ctx), damping = p_.damping.Get(ctx);
  if (c <= 0.0 && damping <= 0.0) return;
  if (ctx.modes[0] == 0.0) {
    d->force_s[0] = -c;
    d->force_v = -damping;
    d->rate_v[0] = 1.0;
  } else if (damping > 0.0) {
    d->rate_s[0][0] = -c / damping;
  }
}

StickSlipHold ElasticFrictionForce::Hold(const ElementContext& ctx, double mode) const {
  // switched off: nothing measured, no crossing can trigger
  if (!(p_.damping.Get(ctx) > 0.0 || p_.stiffness.Get(ctx) > 0.0)) return {.active = false};
  const Values r = Compute(ctx, mode);
  return {.slip_rate = r.v - r.delta_rate,
          .holding = r.tension,
          .static_limit = p_.ratio.Get(ctx) * p_.friction.Get(ctx)};
}

void ElasticFrictionForce::OnSwitch(const ElementContext& ctx, double, double to, std::span<double> state) const {
  // d = 0: the link jumps from k_s F / c to F / c when the slider lets go
  // (the reset map of docs/ELEMENTS.md 3.7); with d > 0 delta is continuous.
  if (to != kStick && p_.damping.Get(ctx) <= 0.0) state[0] = SlidingDeflection(ctx, to);
}

double ElasticFrictionForce::SlidingDeflection(const ElementContext& ctx, double mode) const {
  const double c = p_.stiffness.Get(ctx);
  if (mode == 0.0 || p_.damping.Get(ctx) > 0.0 || c <= 0.0) return 0.0;
  return mode * p_.friction.Get(ctx) / c;
}

ElementCoordinate ElasticFrictionForce::Coordinate(const std::string& component) const {
  return component.empty() ? ElementCoordinate::Line(body1_, point1_, body2_, point2_) : ElementCoordinate{};
}

std::string ElasticFrictionForce::LinearisedAs(std::span<const double> modes) const {
  if (modes[0] == 0.0) return "stuck: its elastic link (spring c with damper d in series) enters the modes";
  return StickSlip::Sliding(modes[0]) +
         ": a constant force across it; its link relaxes through the slider (a real mode, time constant d/c)";
}

}  // namespace mechflow::mech
