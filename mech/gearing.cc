#include "mech/gearing.h"

#include <sstream>

#include "mech/errors.h"

namespace mechflow::mech {

namespace {
constexpr double kEngageMargin = 1e-12;  // [m], see ZeroCrossings
}  // namespace

Gearing::Gearing(std::string name, std::string origin, int body1, Vec3 centre1, Vec3 axis1, int body2,
                 Vec3 centre2, Vec3 axis2, GearParameters parameters, const Kinematics& initial)
    : ForceElement(std::move(name), std::move(origin)),
      body1_(body1),
      body2_(body2),
      centre1_(centre1),
      centre2_(centre2),
      p_(parameters) {
  DeclareBodies({body1_, body2_});
  const std::string where = this->origin() + (this->origin().empty() ? "" : ": ") + "gearing '" + this->name() + "': ";
  if (!(axis1.norm() > 0) || !(axis2.norm() > 0)) throw InputError(where + "the gear axes must be non-zero");
  if (!(p_.ratio > 0) || p_.clearance < 0 || p_.stiffness < 0 || p_.damping < 0)
    throw InputError(where + "ratio must be positive; clearance, stiffness and damping >= 0");
  axis1_ = axis1.normalized();
  axis2_ = axis2.normalized();
  // the kind of axes is fixed by the mechanism (bearings keep it); decide it once
  const Vec3 o1 = PointPosition(initial, body1_, centre1_), o2 = PointPosition(initial, body2_, centre2_);
  double gap = 0;
  axes_ = ClassifyGearAxes(o1, initial.body_pose[body1_].R * axis1_, o2, initial.body_pose[body2_].R * axis2_, &gap);
  if (axes_ == GearAxes::kSkew) {
    std::ostringstream out;
    out << where << "the gear axes are skew (they pass " << gap
        << " m apart); gearing needs parallel (spur) or intersecting (bevel) axes";
    throw InputError(out.str());
  }
  const PitchGeometry g = Pitch(initial);
  if (g.problem) throw InputError(where + g.problem);
  for (const char* s : {"force", "deflection", "mode"}) DeclareSensor(s);
  DeclareStates(1);
  DeclareModes(1);
  DeclareCrossing(mech::Crossing::kEither);  // delta - b/2
  DeclareCrossing(mech::Crossing::kEither);  // delta + b/2
}

PitchGeometry Gearing::Pitch(const Kinematics& kin) const {
  const Vec3 o1 = PointPosition(kin, body1_, centre1_), o2 = PointPosition(kin, body2_, centre2_);
  const Vec3 a1 = kin.body_pose[body1_].R * axis1_;
  if (axes_ == GearAxes::kParallel) return ParallelPitch(o1, a1, o2, p_.ratio);
  return BevelPitch(o1, a1, o2, kin.body_pose[body2_].R * axis2_, p_.ratio);
}

Gearing::Mesh Gearing::Geometry(const ElementContext& ctx) const {
  const Kinematics& kin = *ctx.kin;
  const PitchGeometry g = Pitch(kin);
  if (g.problem) {
    std::ostringstream out;
    out << "gearing '" << name() << "': " << g.problem << " at t = " << ctx.t;
    throw SimulationError(out.str());
  }
  Mesh m;
  m.p = g.p;
  m.t = g.t;
  m.rate = (MaterialVelocityAt(kin, body1_, m.p) - MaterialVelocityAt(kin, body2_, m.p)).dot(m.t);
  return m;
}

double Gearing::ModeFor(double delta, double rate) const {
  const double half = 0.5 * p_.clearance;
  if (delta > half || (delta == half && rate > 0)) return 1.0;
  if (delta < -half || (delta == -half && rate < 0)) return -1.0;
  return 0.0;
}

void Gearing::Initialize(const ElementContext& ctx, std::span<double> state, std::span<double> modes) const {
  state[0] = 0.0;
  modes[0] = ModeFor(0.0, Geometry(ctx).rate);
}

std::string Gearing::LinearisedAs(std::span<const double> modes) const {
  if (modes[0] == 0.0) return "in its backlash: the teeth are apart, no mesh stiffness couples the gears";
  return std::string("in mesh on its ") + (modes[0] > 0 ? "positive" : "negative") +
         " flank: the mesh stiffness and damping couple the gears";
}

bool Gearing::UpdateModes(const ElementContext& ctx, std::span<double> state, std::span<double> modes) const {
  const double mode = ModeFor(state[0], Geometry(ctx).rate);
  const bool changed = mode != modes[0];
  modes[0] = mode;
  return changed;
}

void Gearing::Evaluate(const ElementContext& ctx, Loads* loads, std::span<double> state_rate,
                       std::span<double> sensors) const {
  const Mesh m = Geometry(ctx);
  const double delta = ctx.state[0], mode = ctx.modes[0];
  double f = 0.0;
  if (mode != 0.0) {
    f = p_.stiffness * (delta - mode * 0.5 * p_.clearance) + p_.damping * m.rate;
    if (f * mode < 0) f = 0.0;  // teeth never pull
  }
  loads->AddForce(*ctx.kin, body1_, m.p, -f * m.t);
  loads->AddForce(*ctx.kin, body2_, m.p, f * m.t);
  state_rate[0] = m.rate;
  sensors[0] = f;
  sensors[1] = delta;
  sensors[2] = mode;
}

void Gearing::ZeroCrossings(const ElementContext& ctx, std::span<double> values) const {
  // Free (mode 0), the engagement crossings sit 1e-12 m beyond the backlash:
  // gears at rest with no clearance start exactly at delta = 0, and the
  // solver reports no crossing of a function that starts at zero. (A tooth
  // force of c * 1e-12 m is far below any tolerance.)
  const double margin = ctx.modes[0] == 0.0 ? kEngageMargin : 0.0;
  values[0] = ctx.state[0] - 0.5 * p_.clearance - margin;
  values[1] = ctx.state[0] + 0.5 * p_.clearance + margin;
}

}  // namespace mechflow::mech
