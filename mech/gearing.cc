#include "mech/gearing.h"

#include <sstream>

#include "mech/errors.h"

namespace mechflow::mech {

Gearing::Gearing(std::string name, std::string origin, int body1, Vec3 centre1, Vec3 axis1, int body2,
                 Vec3 centre2, GearParameters parameters)
    : ForceElement(std::move(name), std::move(origin)),
      body1_(body1),
      body2_(body2),
      centre1_(centre1),
      centre2_(centre2),
      p_(parameters) {
  const std::string where = this->origin() + (this->origin().empty() ? "" : ": ") + "gearing '" + this->name() + "': ";
  if (!(axis1.norm() > 0)) throw InputError(where + "the axis of gear 1 must be non-zero");
  if (!(p_.ratio > 0) || p_.clearance < 0 || p_.stiffness < 0 || p_.damping < 0)
    throw InputError(where + "ratio must be positive; clearance, stiffness and damping >= 0");
  axis1_ = axis1.normalized();
  for (const char* s : {"force", "deflection", "mode"}) DeclareSensor(s);
  DeclareStates(1);
  DeclareModes(1);
  DeclareCrossing(mech::Crossing::kEither);  // delta - b/2
  DeclareCrossing(mech::Crossing::kEither);  // delta + b/2
}

Gearing::Mesh Gearing::Geometry(const ElementContext& ctx) const {
  const Kinematics& kin = *ctx.kin;
  const Vec3 o1 = PointPosition(kin, body1_, centre1_), o2 = PointPosition(kin, body2_, centre2_);
  const Vec3 a1 = kin.body_pose[body1_].R * axis1_;
  const Vec3 d = (o2 - o1) - (o2 - o1).dot(a1) * a1;
  const double distance = d.norm();
  if (!(distance > 0)) {
    std::ostringstream out;
    out << "gearing '" << name() << "': the gear centres are on one axis at t = " << ctx.t;
    throw SimulationError(out.str());
  }
  const Vec3 u = d / distance;
  Mesh m;
  m.p = o1 + distance * p_.ratio / (1 + p_.ratio) * u;
  m.t = a1.cross(u);
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
  values[0] = ctx.state[0] - 0.5 * p_.clearance;
  values[1] = ctx.state[0] + 0.5 * p_.clearance;
}

}  // namespace mechflow::mech
