#include "mech/points_plane_contact.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "mech/errors.h"

namespace mechflow::mech {
namespace {

std::string FormatNumber(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", v);
  return buffer;
}

}  // namespace

double ContactNormalForce(const ContactLaw& law, double delta, double rate) {
  if (delta <= 0) return 0.0;
  double damping = law.damping;
  if (law.damping_depth > 0) {
    const double s = std::min(delta / law.damping_depth, 1.0);
    damping *= s * s * (3 - 2 * s);
  }
  return std::max(0.0, law.stiffness * std::pow(delta, law.exponent) + damping * rate);
}

double ContactEnergy(const ContactLaw& law, double delta) {
  return delta > 0 ? law.stiffness * std::pow(delta, law.exponent + 1) / (law.exponent + 1) : 0.0;
}

void CheckContactLaw(const ContactLaw& law, const std::string& where) {
  auto require = [&](bool ok, const char* what, double value) {
    if (!ok) throw InputError(where + what + " (found " + FormatNumber(value) + ")");
  };
  require(law.exponent >= 1.0, "the stiffness exponent must be at least 1", law.exponent);
  require(law.stiffness >= 0, "the stiffness must be >= 0", law.stiffness);
  require(law.damping >= 0, "the damping must be >= 0", law.damping);
  require(law.damping_depth >= 0, "damping_depth must be >= 0", law.damping_depth);
  require(law.mu >= 0, "the friction coefficient mu must be >= 0", law.mu);
  require(law.mu_static >= law.mu, "mu_static must not be below mu (static below dynamic friction)",
          law.mu_static);
  require(law.stribeck_velocity > 0, "stribeck_velocity must be > 0", law.stribeck_velocity);
  require(law.v_eps > 0, "v_eps must be > 0", law.v_eps);
  require(law.max_penetration > 0, "max_penetration must be > 0", law.max_penetration);
}

std::string PenetrationWarning(const ContactLaw& law) {
  return "penetration exceeds max_penetration = " + FormatNumber(law.max_penetration) +
         " m (is the contact too soft, or is a body passing through the plane?)";
}

double PlaneDepth(const Kinematics& kin, int body2, const Vec3& plane_point, const Vec3& normal, const Vec3& p) {
  const Pose& plane = kin.body_pose[body2];
  return -(p - plane * plane_point).dot(plane.R * normal);
}

std::string StartPenetrationWarning(const ElementContext& ctx, const std::string& name, const ContactLaw& law,
                                    double depth, int body1, int body2, const Vec3& plane_point, const Vec3& normal) {
  if (!(depth > law.max_penetration)) return "";
  // m, with mm alongside: contacts are set in m, their depths read in mm
  auto length = [](double m) { return FormatNumber(m) + " m (" + FormatNumber(m * 1e3) + " mm)"; };
  const std::string start = "contact '" + name + "' starts " + length(depth) +
                            " inside its plane, beyond its max_penetration " + length(law.max_penetration);
  const Body& body = ctx.model->bodies()[body1];
  const bool fixed = body.segment == kGround;
  if (!fixed && PlaneDepth(*ctx.kin, body2, plane_point, normal, PointPosition(*ctx.kin, body1, body.com)) > 0)
    return start + ", with the centre of mass of body '" + body.name + "' inside too: the plane's normal likely " +
           "points into '" + body.name + "'; it must point out of body2 '" + ctx.model->bodies()[body2].name +
           "' toward body1 (else check the bodies' initial positions)";
  return start + ": check the bodies' initial positions and the plane's point and normal";
}

std::string ContactLinearisedAs(std::span<const double> modes) {
  int touching = 0;
  for (const double m : modes) touching += m != 0.0;
  if (touching == 0) return "not touching: no contact stiffness";
  return std::to_string(touching) + " of " + std::to_string(modes.size()) +
         " point(s) touching: their contact stiffness acts, and below a slip of v_eps their regularised "
         "friction acts as a steep viscous damper (mu N / v_eps per point)";
}

PointContactLoad ApplyPointContact(const Kinematics& kin, const ContactLaw& law, int body1, int body2,
                                   const Vec3& p, const Vec3& n, double delta, Loads* loads) {
  const Vec3 w = MaterialVelocityAt(kin, body1, p) - MaterialVelocityAt(kin, body2, p);
  PointContactLoad out;
  out.normal = ContactNormalForce(law, std::max(delta, 0.0), -w.dot(n));
  const Vec3 wt = w - w.dot(n) * n;
  out.slip = wt.norm();
  const double stribeck = out.slip / law.stribeck_velocity;
  const double mu = law.mu + (law.mu_static - law.mu) * std::exp(-stribeck * stribeck);
  out.friction = -mu * out.normal * wt / std::sqrt(wt.squaredNorm() + law.v_eps * law.v_eps);
  const Vec3 load = out.normal * n + out.friction;
  loads->AddForce(kin, body1, p, load);
  loads->AddForce(kin, body2, p, -load);
  return out;
}

PointsPlaneContact::PointsPlaneContact(std::string name, std::string origin, int body1, std::vector<Vec3> points,
                                       int body2, Vec3 plane_point, Vec3 normal, ContactLaw law)
    : ForceElement(std::move(name), std::move(origin)),
      body1_(body1),
      body2_(body2),
      points_(std::move(points)),
      plane_point_(plane_point),
      law_(law) {
  DeclareBodies({body1_, body2_});
  const std::string where = this->origin() + (this->origin().empty() ? "" : ": ") + "contact '" + this->name() + "': ";
  if (points_.empty()) throw InputError(where + "needs at least one point");
  if (!(normal.norm() > 0)) throw InputError(where + "the plane normal must be non-zero");
  CheckContactLaw(law_, where);
  normal_ = normal.normalized();
  for (const char* s : {"normal", "penetration", "slip", "friction", "energy"}) DeclareSensor(s);
  DeclareModes(static_cast<int>(points_.size()));
  for (std::size_t i = 0; i < points_.size(); ++i) DeclareCrossing(mech::Crossing::kEither);
  DeclareCrossing(mech::Crossing::kRising);  // the deepest point passes max_penetration
}

std::string PointsPlaneContact::LinearisedAs(std::span<const double> modes) const {
  return ContactLinearisedAs(modes);
}

std::string PointsPlaneContact::CrossingWarning(int index, int direction) const {
  return index == static_cast<int>(points_.size()) && direction > 0 ? PenetrationWarning(law_) : "";
}

std::string PointsPlaneContact::StartWarning(const ElementContext& ctx) const {
  Vec3 p;
  double deepest = -1e300;
  for (std::size_t i = 0; i < points_.size(); ++i) deepest = std::max(deepest, Penetration(ctx, static_cast<int>(i), &p));
  return StartPenetrationWarning(ctx, name(), law_, deepest, body1_, body2_, plane_point_, normal_);
}

double PointsPlaneContact::Penetration(const ElementContext& ctx, int i, Vec3* p) const {
  *p = PointPosition(*ctx.kin, body1_, points_[i]);
  return PlaneDepth(*ctx.kin, body2_, plane_point_, normal_, *p);
}

void PointsPlaneContact::Initialize(const ElementContext& ctx, std::span<double>, std::span<double> modes) const {
  Vec3 p;
  for (std::size_t i = 0; i < points_.size(); ++i) modes[i] = Penetration(ctx, static_cast<int>(i), &p) > 0 ? 1 : 0;
}

void PointsPlaneContact::Evaluate(const ElementContext& ctx, Loads* loads, std::span<double>,
                                  std::span<double> sensors) const {
  const Kinematics& kin = *ctx.kin;
  const Vec3 n = kin.body_pose[body2_].R * normal_;
  double total_normal = 0, deepest = -1e300, slip = 0, loaded = -1, energy = 0;
  Vec3 friction = Vec3::Zero();
  for (std::size_t i = 0; i < points_.size(); ++i) {
    Vec3 p;
    const double delta = Penetration(ctx, static_cast<int>(i), &p);
    deepest = std::max(deepest, delta);
    if (ctx.modes[i] == 0.0) continue;
    const PointContactLoad c = ApplyPointContact(kin, law_, body1_, body2_, p, n, delta, loads);
    energy += ContactEnergy(law_, delta);
    total_normal += c.normal;
    friction += c.friction;
    if (c.normal > loaded) loaded = c.normal, slip = c.slip;
  }
  sensors[0] = total_normal;
  sensors[1] = deepest;
  sensors[2] = slip;
  sensors[3] = friction.norm();
  sensors[4] = energy;
}

void PointsPlaneContact::ZeroCrossings(const ElementContext& ctx, std::span<double> values) const {
  Vec3 p;
  double deepest = -1e300;
  for (std::size_t i = 0; i < points_.size(); ++i) {
    values[i] = Penetration(ctx, static_cast<int>(i), &p);
    deepest = std::max(deepest, values[i]);
  }
  values[points_.size()] = deepest - law_.max_penetration;
}

bool PointsPlaneContact::UpdateModes(const ElementContext& ctx, std::span<double>, std::span<double> modes) const {
  const Vec3 n = ctx.kin->body_pose[body2_].R * normal_;
  bool changed = false;
  for (std::size_t i = 0; i < points_.size(); ++i) {
    Vec3 p;
    const double delta = Penetration(ctx, static_cast<int>(i), &p);
    const Vec3 w = PointVelocity(*ctx.kin, body1_, points_[i]) - MaterialVelocityAt(*ctx.kin, body2_, p);
    const double mode = delta > 0 || (delta == 0 && -w.dot(n) > 0) ? 1.0 : delta < 0 ? 0.0 : modes[i];
    changed |= mode != modes[i];
    modes[i] = mode;
  }
  return changed;
}

void PointsPlaneContact::OnCrossing(int index, int direction, const ElementContext&, std::span<double>,
                                    std::span<double> modes) const {
  if (index == static_cast<int>(points_.size())) return;  // the bound: a warning only
  modes[index] = direction > 0 ? 1.0 : 0.0;
}

ElementCoordinate PointsPlaneContact::Coordinate(const std::string& component) const {
  return component.empty() ? ElementCoordinate::Penetration(body1_, body2_, normal_) : ElementCoordinate{};
}

}  // namespace mechflow::mech
