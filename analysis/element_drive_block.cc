#include "analysis/element_drive_block.h"

#include <cmath>
#include <numbers>

#include "mech/errors.h"

namespace mechflow::analysis {
namespace {

using Kind = mech::ElementCoordinate::Kind;

enum Port { kX, kV, kForce, kReaction };

}  // namespace

struct ElementDriveBlock::Scratch final : blocks::BlockScratch {
  Scratch(const mech::Mechanism& mechanism, const mech::ForceElement& element, const std::vector<double>& q0)
      : kin(mechanism.model()),
        q(q0),
        v(mechanism.model().nv(), 0.0),
        args(1 + mechanism.num_inputs(), 0.0),
        sensors(element.num_sensors(), 0.0),
        rates(element.num_states(), 0.0),
        loads(mechanism.model()),
        element_scratch(element.MakeScratch()) {}

  mech::Kinematics kin;
  std::uint64_t contexts = 0;  // how many Context made: the kinematics' stamp, new for each
  std::vector<double> q, v, args, sensors, rates;
  mech::Loads loads;
  std::unique_ptr<mech::ElementScratch> element_scratch;
};

std::unique_ptr<blocks::BlockScratch> ElementDriveBlock::MakeScratch() const {
  return std::make_unique<Scratch>(mechanism_, element_, q0_);
}

ElementDriveBlock::ElementDriveBlock(std::string name, const mech::Mechanism& mechanism, int element,
                                     const std::string& component, HarmonicDrive drive)
    : Block("element_drive", std::move(name)),
      mechanism_(mechanism),
      element_(mechanism.element(element)),
      coordinate_(element_.Coordinate(component)),
      drive_(drive),
      kin0_(mechanism.model()),
      q0_(mechanism.model().initial_q()) {
  const std::string what = (element_.origin().empty() ? "" : element_.origin() + ": ") + "element '" +
                           element_.name() + "'" + (component.empty() ? "" : " component '" + component + "'");
  if (coordinate_.kind == Kind::kNone) {
    const bool bushing = element_.FindSensor("dx") >= 0;
    if (bushing)
      throw InputError(what + (component.empty() ? " needs a component to drive (--component)"
                                                 : " is not one of a bushing's components") +
                       ": dx, dy, dz, ax, ay or az");
    throw InputError(what + " has no scalar coordinate to drive" +
                     (component.empty() ? "" : " (components are a bushing's)"));
  }
  if (element_.exact_stick())
    throw InputError(what + " sticks exactly: while stuck it has no force of its own, only what the mechanism "
                            "needs; to analyse it, give a friction element a stick stiffness (stick=\"spring\", c, "
                            "d), a contact stick=\"regularised\"");
  if (element_.depends_on_inputs())
    throw InputError(what + " has parameters that follow signal inputs, which force analysis does not drive; "
                            "give them values through identifiers (--set)");
  if (!(drive_.frequency > 0.0) || !std::isfinite(drive_.frequency))
    throw InputError("force analysis: the frequency must be > 0 Hz");
  if (!std::isfinite(drive_.amplitude)) throw InputError("force analysis: the amplitude must be a number");

  const mech::Model& model = mechanism.model();
  const std::vector<double> at_rest(model.nv(), 0.0);
  mech::UpdateKinematics(model, 0.0, q0_, at_rest, &kin0_);
  auto is_ground = [&](int body) { return body < 0 || model.bodies()[body].segment == mech::kGround; };
  switch (coordinate_.kind) {
    case Kind::kLine: {
      const mech::Vec3 d = mech::PointPosition(kin0_, coordinate_.body2, coordinate_.point2) -
                     mech::PointPosition(kin0_, coordinate_.body1, coordinate_.point1);
      if (!(d.norm() > 0.0))
        throw InputError(what + " has zero length in the initial configuration: its line has no direction");
      direction_ = d.normalized();
      mover_ = coordinate_.body2;
      break;
    }
    case Kind::kPenetration:  // deeper: body 1 against the plane's normal
      direction_ = -(kin0_.body_pose[coordinate_.body2].R * coordinate_.axis);
      mover_ = coordinate_.body1;
      break;
    case Kind::kTranslation:
    case Kind::kRotation:
      direction_ = kin0_.body_pose[coordinate_.body1].R * coordinate_.axis;
      pivot_ = mech::PointPosition(kin0_, coordinate_.body2, coordinate_.point2);
      mover_ = coordinate_.body2;
      break;
    case Kind::kJoint:
    case Kind::kNone:
      break;
  }
  // moving the other body the other way does the same to the coordinate
  if (coordinate_.kind != Kind::kJoint && is_ground(mover_)) {
    mover_ = mover_ == coordinate_.body1 ? coordinate_.body2 : coordinate_.body1;
    direction_ = -direction_;
    if (is_ground(mover_))
      throw InputError(what + " acts between two bodies fixed to the ground: nothing can be driven");
  }

  DeclareOutputPort("x");
  DeclareOutputPort("v");
  DeclareOutputPort("force");
  DeclareOutputPort("reaction");
  DeclareNoFeedthrough();
  if (element_.num_states() > 0) DeclareContinuousStates(element_.num_states(), "element");
  DeclareDiscreteStates(element_.num_modes());
  for (int i = 0; i < element_.num_crossings(); ++i) {
    const mech::Crossing c = element_.crossing_direction(i);
    DeclareZeroCrossing(c == mech::Crossing::kRising    ? blocks::CrossingDirection::kRising
                        : c == mech::Crossing::kFalling ? blocks::CrossingDirection::kFalling
                                                        : blocks::CrossingDirection::kEither);
  }
  // x0: the coordinate in the initial configuration, as the element measures
  // it (a contact's deepest point, a bushing's deflection)
  std::vector<double> state(element_.num_states(), 0.0), modes(element_.num_modes(), 0.0);
  Scratch s(mechanism_, element_, q0_);
  element_.Initialize(Context(s, 0.0, state, modes, false), state, modes);
  element_.Evaluate(Context(s, 0.0, state, modes, false), &s.loads, s.rates, s.sensors);
  x0_ = s.sensors[coordinate_.coordinate_sensor];
}

mech::ElementContext ElementDriveBlock::Context(Scratch& s, double t, std::span<const double> state,
                                                std::span<const double> modes, bool driven) const {
  const double w = 2.0 * std::numbers::pi * drive_.frequency, angle = w * t + drive_.phase,
               a = driven ? drive_.amplitude : 0.0;
  const double shift = a * std::sin(angle), rate = a * w * std::cos(angle);
  s.kin = kin0_;
  s.kin.time = t;
  s.kin.stamp = ++s.contexts;  // moved by hand below: what the element measured before no longer holds
  if (coordinate_.kind == Kind::kJoint) {
    s.q[coordinate_.q_index] = q0_[coordinate_.q_index] + shift;
    s.v[coordinate_.v_index] = rate;
  } else if (coordinate_.kind == Kind::kRotation) {
    mech::Pose& pose = s.kin.body_pose[mover_];
    const mech::Mat3 turn = mech::AxisRotation(direction_, shift);
    pose.R = turn * pose.R;
    pose.p = pivot_ + turn * (pose.p - pivot_);
    s.kin.body_omega[mover_] = rate * direction_;
    s.kin.body_velocity[mover_] = s.kin.body_omega[mover_].cross(pose.p - pivot_);
  } else {
    s.kin.body_pose[mover_].p += shift * direction_;
    s.kin.body_velocity[mover_] = rate * direction_;
  }
  s.args[0] = t;
  mech::ElementContext ctx;
  ctx.t = t;
  ctx.model = &mechanism_.model();
  ctx.kin = &s.kin;
  ctx.q = s.q;
  ctx.v = s.v;
  ctx.parameter_args = s.args;
  ctx.state = state;
  ctx.modes = modes;
  ctx.scratch = s.element_scratch.get();
  return ctx;
}

void ElementDriveBlock::Evaluate(const blocks::BlockContext& ctx, Scratch& s, std::span<double> rates) const {
  s.loads.Clear();
  element_.Evaluate(Context(s, ctx.time(), ctx.state(), ctx.discrete()), &s.loads, rates, s.sensors);
}

void ElementDriveBlock::DoInitialize(const blocks::BlockContext& ctx) const {
  for (double& m : ctx.discrete()) m = 0.0;
  for (double& x : ctx.state()) x = 0.0;
  element_.Initialize(Context(ctx.scratch<Scratch>(), 0.0, ctx.state(), ctx.discrete()), ctx.state(), ctx.discrete());
}

void ElementDriveBlock::DoCalcOutput(int port, const blocks::BlockContext& ctx) const {
  const double w = 2.0 * std::numbers::pi * drive_.frequency, angle = w * ctx.time() + drive_.phase;
  if (port == kX) {
    ctx.output(port)[0] = drive_.amplitude * std::sin(angle);
  } else if (port == kV) {
    ctx.output(port)[0] = drive_.amplitude * w * std::cos(angle);
  } else {
    Scratch& s = ctx.scratch<Scratch>();
    Evaluate(ctx, s, s.rates);
    const double force = coordinate_.force_sign * s.sensors[coordinate_.force_sensor];
    ctx.output(port)[0] = port == kForce ? force : -force;
  }
}

void ElementDriveBlock::DoCalcDerivatives(const blocks::BlockContext& ctx) const {
  if (element_.num_states() == 0) return;
  Evaluate(ctx, ctx.scratch<Scratch>(), ctx.derivative());
}

void ElementDriveBlock::DoCalcZeroCrossings(const blocks::BlockContext& ctx) const {
  element_.ZeroCrossings(Context(ctx.scratch<Scratch>(), ctx.time(), ctx.state(), ctx.discrete()),
                         ctx.zero_crossings());
}

void ElementDriveBlock::DoZeroCrossing(int index, int direction, const blocks::BlockContext& ctx) const {
  element_.OnCrossing(index, direction, Context(ctx.scratch<Scratch>(), ctx.time(), ctx.state(), ctx.discrete()),
                      ctx.state(), ctx.discrete());
}

bool ElementDriveBlock::DoUpdateModes(const blocks::BlockContext& ctx) const {
  if (element_.num_modes() == 0) return false;
  return element_.UpdateModes(Context(ctx.scratch<Scratch>(), ctx.time(), ctx.state(), ctx.discrete()), ctx.state(),
                              ctx.discrete());
}

}  // namespace mechflow::analysis
