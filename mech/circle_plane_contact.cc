#include "mech/circle_plane_contact.h"

#include <cmath>
#include <sstream>

#include "mech/errors.h"

namespace mechflow::mech {

CirclePlaneContact::CirclePlaneContact(std::string name, std::string origin, int body1, Vec3 centre,
                                       Vec3 circle_normal, double radius, int body2, Vec3 plane_point, Vec3 normal,
                                       ContactLaw law)
    : ForceElement(std::move(name), std::move(origin)),
      body1_(body1),
      body2_(body2),
      centre_(centre),
      radius_(radius),
      plane_point_(plane_point),
      law_(law) {
  DeclareBodies({body1_, body2_});
  const std::string where = this->origin() + (this->origin().empty() ? "" : ": ") + "contact '" + this->name() + "': ";
  if (!(circle_normal.norm() > 0)) throw InputError(where + "the circle normal must be non-zero");
  if (!(normal.norm() > 0)) throw InputError(where + "the plane normal must be non-zero");
  if (!(radius > 0)) throw InputError(where + "the radius must be positive");
  CheckContactLaw(law_, where);
  circle_normal_ = circle_normal.normalized();
  normal_ = normal.normalized();
  PlaneTangents(normal_, &tangent1_, &tangent2_);
  for (const char* s : {"normal", "penetration", "slip", "friction", "energy"}) DeclareSensor(s);
  DeclareModes(1);
  DeclareCrossing(mech::Crossing::kEither);
  DeclareCrossing(mech::Crossing::kRising);  // max_penetration passed
  if (!law_.exact_stick) return;
  stick_.emplace(law_);
  DeclareSensor("mode_1");
  DeclareModes(ContactStick::kModesPerPoint);
  DeclareCrossing(ContactStick::BreakawayDirection());
  DeclareCrossing(ContactStick::SlipEndDirection());
  DeclareCrossing(ContactStick::SteerDirection());
  DeclareExactStick(2);
}

std::string CirclePlaneContact::LinearisedAs(std::span<const double> modes) const {
  return ContactLinearisedAs(modes.first(1), stick_.has_value());
}

std::string CirclePlaneContact::CrossingWarning(int index, int direction) const {
  return index == 1 && direction > 0 ? PenetrationWarning(law_) : "";
}

double CirclePlaneContact::Geometry(const ElementContext& ctx, Vec3* q, Vec3* n, Vec3* q_rate) const {
  const Kinematics& kin = *ctx.kin;
  const Pose& plane = kin.body_pose[body2_];
  *n = plane.R * normal_;
  const Vec3 c = PointPosition(kin, body1_, centre_);
  const Vec3 nc = kin.body_pose[body1_].R * circle_normal_;
  const Vec3 in_plane = *n - n->dot(nc) * nc;
  const double size = in_plane.norm();
  if (!(size > 1e-12)) {
    std::ostringstream out;
    out << "contact '" << name() << "': the circle lies flat on the plane at t = " << ctx.t
        << " (no single deepest point)";
    throw SimulationError(out.str());
  }
  const Vec3 u = -in_plane / size;
  *q = c + radius_ * u;
  if (q_rate) {
    // Q = C + R u with u = -a / |a|, a = N - (N . n_c) n_c: N and n_c turn
    // with their bodies, and u' is a' without its component along u
    const Vec3 n_rate = kin.body_omega[body2_].cross(*n), nc_rate = kin.body_omega[body1_].cross(nc);
    const Vec3 a_rate = n_rate - (n_rate.dot(nc) + n->dot(nc_rate)) * nc - n->dot(nc) * nc_rate;
    const Vec3 u_rate = -(a_rate - u.dot(a_rate) * u) / size;
    *q_rate = PointVelocity(kin, body1_, centre_) + radius_ * u_rate;
  }
  return radius_ * size + PlaneDepth(kin, body2_, plane_point_, normal_, c);
}

ContactPointMotion CirclePlaneContact::Motion(const ElementContext& ctx, double* delta) const {
  Vec3 q, n, q_rate;
  *delta = Geometry(ctx, &q, &n, &q_rate);
  return MeasureContactPoint(*ctx.kin, body1_, body2_, q, q_rate, n, tangent1_, tangent2_);
}

std::string CirclePlaneContact::StartWarning(const ElementContext& ctx) const {
  Vec3 q, n;
  return StartPenetrationWarning(ctx, name(), law_, Geometry(ctx, &q, &n), body1_, body2_, plane_point_, normal_);
}

void CirclePlaneContact::Initialize(const ElementContext& ctx, std::span<double>, std::span<double> modes) const {
  double delta;
  const ContactPointMotion m = Motion(ctx, &delta);
  modes[0] = delta > 0 ? 1.0 : 0.0;
  if (stick_) ContactStick::Start(m, StickModes(modes));
}

bool CirclePlaneContact::ModesAtRest(const ElementContext& ctx, std::span<double>, std::span<double> modes) const {
  const double before = modes[0];
  Vec3 q, n;
  modes[0] = Geometry(ctx, &q, &n) > 0 ? 1.0 : 0.0;
  bool changed = modes[0] != before;
  if (stick_ && modes[0] != 0.0 && StickModes(modes)[0] != ContactStick::kStuck) {
    double delta;
    ContactStick::Start(Motion(ctx, &delta), StickModes(modes));  // at rest: stuck
    changed = true;
  }
  return changed;
}

bool CirclePlaneContact::UpdateModes(const ElementContext& ctx, std::span<double>, std::span<double> modes) const {
  if (!stick_ || modes[0] == 0.0) return false;
  double delta;
  const ContactPointMotion m = Motion(ctx, &delta);
  return stick_->Update(NormalForce(m, delta), ctx.stick_forces, StickModes(modes));
}

std::string CirclePlaneContact::CrossingName(int index, int direction) const {
  if (index == 0) return direction > 0 ? "touches" : "leaves";
  if (index == 1) return "penetration passes max_penetration";
  return ContactStick::CrossingName(index - 2);
}

bool CirclePlaneContact::StuckExactly(const ElementContext& ctx, int) const {
  return stick_ && ctx.modes[0] != 0.0 && StickModes(ctx.modes)[0] == ContactStick::kStuck;
}

void CirclePlaneContact::ApplyStickForce(const ElementContext& ctx, int hold, double f, Loads* loads) const {
  double delta;
  ContactStick::ApplyHoldForce(*ctx.kin, Motion(ctx, &delta), hold, f, loads);
}

double CirclePlaneContact::StickAcceleration(const ElementContext& ctx, int hold, const DynamicsWorkspace& dyn,
                                             std::span<const double>) const {
  double delta;
  return ContactStick::HoldAcceleration(*ctx.model, *ctx.kin, dyn, Motion(ctx, &delta), hold);
}

double CirclePlaneContact::HoldVelocity(const ElementContext& ctx, int hold) const {
  double delta;
  const ContactPointMotion m = Motion(ctx, &delta);
  return hold == 0 ? m.s1 : m.s2;
}

void CirclePlaneContact::FollowSlip(const ElementContext& ctx, std::span<double> modes) const {
  if (modes[0] == 0.0) return;
  double delta;
  ContactStick::Follow(Motion(ctx, &delta), StickModes(modes));
}

std::string CirclePlaneContact::HoldName(int) const { return "contact '" + name() + "'"; }

void CirclePlaneContact::Evaluate(const ElementContext& ctx, Loads* loads, std::span<double>,
                                  std::span<double> sensors) const {
  PointContactLoad c;
  double delta;
  if (stick_) {
    const ContactPointMotion m = Motion(ctx, &delta);
    sensors[5] = ctx.modes[0] == 0.0 ? 0.0 : StickModes(ctx.modes)[0] == ContactStick::kStuck ? 1.0 : 2.0;
    if (ctx.modes[0] != 0.0) {
      c.normal = NormalForce(m, delta);
      c.slip = m.speed();
      c.friction = stick_->Friction(m, c.normal, StickModes(ctx.modes), ctx.stick_forces);
      const Vec3 load = c.normal * m.normal + c.friction;
      loads->AddForce(*ctx.kin, body1_, m.point, load);
      loads->AddForce(*ctx.kin, body2_, m.point, -load);
    }
  } else {
    Vec3 q, n;
    delta = Geometry(ctx, &q, &n);
    if (ctx.modes[0] != 0.0) c = ApplyPointContact(*ctx.kin, law_, body1_, body2_, q, n, delta, loads);
  }
  sensors[0] = c.normal;
  sensors[1] = delta;
  sensors[2] = c.slip;
  sensors[3] = c.friction.norm();
  sensors[4] = ctx.modes[0] != 0.0 ? ContactEnergy(law_, delta) : 0.0;
}

void CirclePlaneContact::ZeroCrossings(const ElementContext& ctx, std::span<double> values) const {
  Vec3 q, n;
  values[0] = Geometry(ctx, &q, &n);
  values[1] = values[0] - law_.max_penetration;
  if (!stick_) return;
  double delta;
  const ContactPointMotion m = Motion(ctx, &delta);
  stick_->ZeroCrossings(m, NormalForce(m, delta), ctx.modes[0] != 0.0, StickModes(ctx.modes), ctx.stick_forces,
                        values.subspan(2, ContactStick::kCrossingsPerPoint));
}

void CirclePlaneContact::OnCrossing(int index, int direction, const ElementContext& ctx, std::span<double>,
                                    std::span<double> modes) const {
  if (index == 1) return;  // the bound: a warning only
  double delta;
  if (index == 0) {
    modes[0] = direction > 0 ? 1.0 : 0.0;
    if (stick_ && direction > 0) ContactStick::Start(Motion(ctx, &delta), StickModes(modes));
    return;
  }
  ContactStick::OnCrossing(index - 2, Motion(ctx, &delta), ctx.stick_forces, StickModes(modes));
}

ElementCoordinate CirclePlaneContact::Coordinate(const std::string& component) const {
  return component.empty() ? ElementCoordinate::Penetration(body1_, body2_, normal_) : ElementCoordinate{};
}

}  // namespace mechflow::mech
