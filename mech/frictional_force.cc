#include "mech/frictional_force.h"

#include "mech/dynamics.h"

namespace mechflow::mech {
namespace {

constexpr StickSlip::Wording kWording{"breaks away", "sticks (or turns, when the hold is beyond the limit)"};

}  // namespace

FrictionalForce::FrictionalForce(std::string name, std::string origin, int body1, Vec3 point1, int body2,
                                 Vec3 point2, FrictionalParameters parameters)
    : StickSlipElement(std::move(name), std::move(origin), StickSlip::Order::kSlipEndsFirst, kWording),
      body1_(body1),
      body2_(body2),
      point1_(point1),
      point2_(point2),
      p_(parameters) {
  DeclareBodies({body1_, body2_});
  DeclareInterface();
}

FrictionalForce::FrictionalForce(std::string name, std::string origin, const Dof& dof,
                                 FrictionalParameters parameters)
    : StickSlipElement(std::move(name), std::move(origin), StickSlip::Order::kSlipEndsFirst, kWording),
      q_index_(dof.q_index),
      v_index_(dof.v_index),
      p_(parameters) {
  DeclareCoordinates({v_index_});
  DeclareInterface();
}

void FrictionalForce::DeclareInterface() {
  DeclareDependsOnInputs(p_.friction.uses_inputs || p_.ratio.uses_inputs || p_.stiffness.uses_inputs ||
                         p_.damping.uses_inputs);
  DeclareSensor("force");
  DeclareSensor("length");
  DeclareSensor("rate");
  DeclareSensor("mode");
  DeclareStickSlip();
  // stored energy: none when the hold is exact, the stick spring's otherwise
  if (p_.exact_stick || p_.stiffness.is_constant()) DeclareSensor("energy");
  if (p_.exact_stick) {
    // a friction that is zero for good holds nothing: no holding-force solve
    if (!(p_.friction.is_constant() && p_.friction.value == 0.0)) DeclareExactStick();
  } else {
    DeclareSensor("deflection");  // of the stick spring; 0 while sliding
    // The stick spring's deflection, integrated from the rate while stuck:
    // formed as x - x_s from absolute lengths, its round-off (1e-16 x)
    // times a stiff spring made noise that a tight atol chased (a held block,
    // c = 1e7, atol 1e-14: 135956 steps for 10 s instead of a few hundred).
    DeclareStates(1);
  }
}

FrictionalForce::Slide FrictionalForce::Measure(const ElementContext& ctx) const {
  Slide s;
  if (q_index_ >= 0) {
    s.x = ctx.q[q_index_];
    s.v = ctx.v[v_index_];
    return s;
  }
  s.line = MeasureBipolar(*ctx.kin, body1_, point1_, body2_, point2_);
  s.x = s.line.x;
  s.v = s.line.v;
  return s;
}

void FrictionalForce::Initialize(const ElementContext& ctx, std::span<double> state, std::span<double> modes) const {
  const Slide g = Measure(ctx);
  modes[0] = StickSlip::InitialMode(g.v);
  if (!p_.exact_stick) state[0] = 0.0;
}

void FrictionalForce::Apply(const Slide& g, double f, Loads* loads, const ElementContext& ctx) const {
  if (q_index_ >= 0) {
    loads->AddGeneralizedForce(v_index_, f);
  } else {
    loads->AddForce(*ctx.kin, body2_, g.line.pb, f * g.line.u);
    loads->AddForce(*ctx.kin, body1_, g.line.pa, -f * g.line.u);
  }
}

double FrictionalForce::Holding(const ElementContext& ctx, const Slide& g) const {
  // no holds when the friction is zero for good: nothing to hold
  if (p_.exact_stick) return ctx.stick_forces.empty() ? 0.0 : -ctx.stick_forces[0];
  return p_.stiffness.Get(ctx) * ctx.state[0] + p_.damping.Get(ctx) * g.v;
}

void FrictionalForce::Evaluate(const ElementContext& ctx, Loads* loads, std::span<double> state_rate,
                               std::span<double> sensors) const {
  const Slide g = Measure(ctx);
  const double mode = ctx.modes[0];
  const double f = mode == kStick ? -Holding(ctx, g) : -mode * p_.friction.Get(ctx);
  Apply(g, f, loads, ctx);
  sensors[0] = f;
  sensors[1] = g.x;
  sensors[2] = g.v;
  sensors[3] = mode;
  if (p_.exact_stick) {
    sensors[4] = 0.0;
    return;
  }
  const double deflection = mode == kStick ? ctx.state[0] : 0.0;
  // switched off (c = d = 0): no stick spring, nothing deflects
  const bool spring = p_.stiffness.Get(ctx) != 0.0 || p_.damping.Get(ctx) != 0.0;
  state_rate[0] = mode == kStick && spring ? g.v : 0.0;
  if (p_.stiffness.is_constant()) {
    sensors[4] = 0.5 * p_.stiffness.value * deflection * deflection;
    sensors[5] = deflection;
  } else {
    sensors[4] = deflection;
  }
}

void FrictionalForce::Derivatives(const ElementContext& ctx, double, double, ElementDerivatives* d) const {
  // sliding: a constant force, a constant deflection; stuck: -c delta - d v, delta' = v
  if (ctx.modes[0] != kStick) return;
  const double c = p_.stiffness.Get(ctx), damping = p_.damping.Get(ctx);
  d->force_s[0] = -c;
  d->force_v = -damping;
  if (c != 0.0 || damping != 0.0) d->rate_v[0] = 1.0;
}

bool FrictionalForce::StuckExactly(const ElementContext& ctx, int) const {
  return exact_stick() && ctx.modes[0] == kStick;
}

void FrictionalForce::ApplyStickForce(const ElementContext& ctx, int, double f, Loads* loads) const {
  Apply(Measure(ctx), f, loads, ctx);
}

double FrictionalForce::HoldVelocity(const ElementContext& ctx, int) const { return Measure(ctx).v; }

double FrictionalForce::StickAcceleration(const ElementContext& ctx, int, const DynamicsWorkspace& dyn,
                                          std::span<const double> vdot) const {
  if (q_index_ >= 0) return vdot[v_index_];
  // x'' = u . (a_B - a_A) + (|w|^2 - (u . w)^2) / x, w the points' relative velocity
  const Kinematics& kin = *ctx.kin;
  const Slide g = Measure(ctx);
  if (!(g.x > 0.0)) return 0.0;
  const Vec3 w = PointVelocity(kin, body2_, point2_) - PointVelocity(kin, body1_, point1_);
  const Vec3 a = PointAcceleration(*ctx.model, kin, dyn, body2_, point2_) -
                 PointAcceleration(*ctx.model, kin, dyn, body1_, point1_);
  return g.line.u.dot(a) + (w.squaredNorm() - g.v * g.v) / g.x;
}

bool FrictionalForce::UpdateModes(const ElementContext& ctx, std::span<double> state, std::span<double> modes) const {
  return StuckExactly(ctx, 0) && SlipWhereHoldFails(ctx, state, modes);
}

StickSlipHold FrictionalForce::Hold(const ElementContext& ctx, double mode) const {
  Slide g;
  if (!ctx.sensors.empty() && q_index_ < 0)
    g.v = ctx.sensors[2];  // its rate, measured by Evaluate on these kinematics
  else
    g = Measure(ctx);
  return {.slip_rate = g.v,
          .holding = mode == kStick ? Holding(ctx, g) : 0.0,
          .static_limit = p_.ratio.Get(ctx) * p_.friction.Get(ctx)};
}

void FrictionalForce::OnSwitch(const ElementContext&, double, double to, std::span<double> state) const {
  if (to == kStick && !p_.exact_stick) state[0] = 0.0;  // the stick spring starts relaxed
}

ElementCoordinate FrictionalForce::Coordinate(const std::string& component) const {
  if (!component.empty()) return {};
  return q_index_ >= 0 ? ElementCoordinate::Joint(q_index_, v_index_)
                       : ElementCoordinate::Line(body1_, point1_, body2_, point2_);
}

std::string FrictionalForce::LinearisedAs(std::span<const double> modes) const {
  if (modes[0] != 0.0)
    return StickSlip::Sliding(modes[0]) + ": a constant friction force, no stiffness or damping across it";
  if (p_.exact_stick)
    return "stuck, held exactly: its relative motion is locked, one coordinate fewer (a zero eigenvalue below "
           "is that lock, not a free motion)";
  return "stuck on its stick spring: the spring's stiffness c and damping d enter the modes (frequencies of "
         "the stick spring, not of free sliding)";
}

}  // namespace mechflow::mech
