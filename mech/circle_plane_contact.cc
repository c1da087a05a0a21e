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
  for (const char* s : {"normal", "penetration", "slip", "friction", "energy"}) DeclareSensor(s);
  DeclareModes(1);
  DeclareCrossing(mech::Crossing::kEither);
  DeclareCrossing(mech::Crossing::kRising);  // max_penetration passed
}

std::string CirclePlaneContact::LinearisedAs(std::span<const double> modes) const {
  return ContactLinearisedAs(modes);
}

std::string CirclePlaneContact::CrossingWarning(int index, int direction) const {
  return index == 1 && direction > 0 ? PenetrationWarning(law_) : "";
}

double CirclePlaneContact::Geometry(const ElementContext& ctx, Vec3* q, Vec3* n) const {
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
  *q = c - radius_ * in_plane / size;
  return radius_ * size + PlaneDepth(kin, body2_, plane_point_, normal_, c);
}

std::string CirclePlaneContact::StartWarning(const ElementContext& ctx) const {
  Vec3 q, n;
  return StartPenetrationWarning(ctx, name(), law_, Geometry(ctx, &q, &n), body1_, body2_, plane_point_, normal_);
}

void CirclePlaneContact::Initialize(const ElementContext& ctx, std::span<double>, std::span<double> modes) const {
  Vec3 q, n;
  modes[0] = Geometry(ctx, &q, &n) > 0 ? 1.0 : 0.0;
}

bool CirclePlaneContact::ModesAtRest(const ElementContext& ctx, std::span<double>, std::span<double> modes) const {
  const double before = modes[0];
  Initialize(ctx, {}, modes);
  return modes[0] != before;
}

void CirclePlaneContact::Evaluate(const ElementContext& ctx, Loads* loads, std::span<double>,
                                  std::span<double> sensors) const {
  Vec3 q, n;
  const double delta = Geometry(ctx, &q, &n);
  PointContactLoad c;
  if (ctx.modes[0] != 0.0) c = ApplyPointContact(*ctx.kin, law_, body1_, body2_, q, n, delta, loads);
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
}

void CirclePlaneContact::OnCrossing(int index, int direction, const ElementContext&, std::span<double>,
                                    std::span<double> modes) const {
  if (index == 1) return;  // the bound: a warning only
  modes[0] = direction > 0 ? 1.0 : 0.0;
}

ElementCoordinate CirclePlaneContact::Coordinate(const std::string& component) const {
  return component.empty() ? ElementCoordinate::Penetration(body1_, body2_, normal_) : ElementCoordinate{};
}

}  // namespace mechflow::mech
