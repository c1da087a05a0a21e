#include "mech/points_plane_contact.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "mech/dynamics.h"
#include "mech/errors.h"

namespace mechflow::mech {

double PlaneDepth(const Kinematics& kin, int body2, const Vec3& plane_point, const Vec3& normal, const Vec3& p) {
  const Pose& plane = kin.body_pose[body2];
  return -(p - plane * plane_point).dot(plane.R * normal);
}

std::string StartPenetrationWarning(const ElementContext& ctx, const std::string& name, const ContactLaw& law,
                                    double depth, int body1, int body2, const Vec3& plane_point, const Vec3& normal) {
  if (!(depth > law.max_penetration)) return "";
  // m, with mm alongside: contacts are set in m, their depths read in mm
  auto length = [](double m) { return ContactNumber(m) + " m (" + ContactNumber(m * 1e3) + " mm)"; };
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

std::string ContactLinearisedAs(std::span<const double> touching_modes, bool exact_stick) {
  int touching = 0;
  for (const double m : touching_modes) touching += m != 0.0;
  if (touching == 0) return "not touching: no contact stiffness";
  const std::string points = std::to_string(touching) + " of " + std::to_string(touching_modes.size()) +
                             " point(s) touching: their contact stiffness acts, ";
  if (exact_stick)
    return points + "and their slip is held exactly while they stick (held motions are locked: a zero "
                    "eigenvalue below is such a lock, not a free motion)";
  return points + "and below a slip of v_eps their regularised friction acts as a steep viscous damper "
                  "(mu N / v_eps per point)";
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
  PlaneTangents(normal_, &tangent1_, &tangent2_);
  for (const char* s : {"normal", "penetration", "slip", "friction", "energy"}) DeclareSensor(s);
  DeclareModes(num_points());
  for (int i = 0; i < num_points(); ++i) DeclareCrossing(mech::Crossing::kEither);
  DeclareCrossing(mech::Crossing::kRising);  // the deepest point passes max_penetration
  if (!law_.exact_stick) return;
  stick_.emplace(law_);
  for (int i = 0; i < num_points(); ++i) DeclareSensor("mode_" + std::to_string(i + 1));
  DeclareModes(ContactStick::kModesPerPoint * num_points());
  for (int i = 0; i < num_points(); ++i) {
    DeclareCrossing(ContactStick::BreakawayDirection());
    DeclareCrossing(ContactStick::SlipEndDirection());
    DeclareCrossing(ContactStick::SteerDirection());
  }
  DeclareExactStick(3);
}

std::string PointsPlaneContact::LinearisedAs(std::span<const double> modes) const {
  return ContactLinearisedAs(modes.first(num_points()), stick_.has_value());
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

ContactPointMotion PointsPlaneContact::Motion(const ElementContext& ctx, int i, double* delta) const {
  Vec3 p;
  *delta = Penetration(ctx, i, &p);
  const Kinematics& kin = *ctx.kin;
  return MeasureContactPoint(kin, body1_, body2_, p, PointVelocity(kin, body1_, points_[i]),
                             kin.body_pose[body2_].R * normal_, tangent1_, tangent2_);
}

struct PointsPlaneContact::Measured final : ElementScratch {
  const Kinematics* kin = nullptr;  // measured on these kinematics
  std::uint64_t stamp = 0;          // at this stamp of them
  std::vector<double> depth;        // penetration, every point
  std::vector<MeasuredPoint> point;  // when first asked for (Point): points off the plane seldom are
  std::vector<char> has_point;
  // MeasurePatch's last patch, for these kinematics and stuck points
  Patch patch;
  std::vector<char> stuck;
  bool patch_valid = false;
};

const PointsPlaneContact::MeasuredPoint& PointsPlaneContact::Point(const ElementContext& ctx, int i) const {
  Measured& at = Measure(ctx);
  if (!at.has_point[i]) {
    MeasuredPoint& point = at.point[i];
    point.motion = Motion(ctx, i, &at.depth[i]);
    point.normal = NormalForce(point.motion, at.depth[i]);
    at.has_point[i] = true;
  }
  return at.point[i];
}

std::unique_ptr<ElementScratch> PointsPlaneContact::MakeScratch() const {
  auto measured = std::make_unique<Measured>();
  measured->depth.resize(points_.size());
  measured->point.resize(points_.size());
  measured->has_point.resize(points_.size());
  measured->stuck.resize(points_.size());
  return measured;
}

PointsPlaneContact::Measured& PointsPlaneContact::Measure(const ElementContext& ctx) const {
  auto* measured = static_cast<Measured*>(ctx.scratch);
  if (!measured) throw std::logic_error("contact '" + name() + "' evaluated without the scratch it makes");
  if (measured->kin == ctx.kin && measured->stamp == ctx.kin->stamp) return *measured;
  Vec3 p;
  for (int i = 0; i < num_points(); ++i) {
    measured->depth[i] = Penetration(ctx, i, &p);
    measured->has_point[i] = false;
  }
  measured->kin = ctx.kin;
  measured->stamp = ctx.kin->stamp;
  measured->patch_valid = false;
  return *measured;
}

void PointsPlaneContact::Initialize(const ElementContext& ctx, std::span<double>, std::span<double> modes) const {
  const Measured& at = Measure(ctx);
  for (int i = 0; i < num_points(); ++i) {
    modes[i] = at.depth[i] > 0 ? 1 : 0;
    if (stick_) ContactStick::Start(Point(ctx, i).motion, StickModes(modes, i));
  }
}

void PointsPlaneContact::Evaluate(const ElementContext& ctx, Loads* loads, std::span<double>,
                                  std::span<double> sensors) const {
  const Kinematics& kin = *ctx.kin;
  const Vec3 n = kin.body_pose[body2_].R * normal_;
  double total_normal = 0, deepest = -1e300, slip = 0, loaded = -1, energy = 0;
  Vec3 friction = Vec3::Zero();
  const Patch no_patch;
  const Patch& patch = stick_ ? MeasurePatch(ctx) : no_patch;
  for (int i = 0; i < num_points(); ++i) {
    PointContactLoad c;
    double delta;
    if (stick_) {
      delta = Measure(ctx).depth[i];
      sensors[5 + i] = ctx.modes[i] == 0.0 ? 0.0 : Stuck(ctx.modes, i) ? 1.0 : 2.0;
      if (ctx.modes[i] != 0.0) {
        const MeasuredPoint& point = Point(ctx, i);
        const ContactPointMotion& m = point.motion;
        c.normal = point.normal;
        c.slip = m.speed();
        c.friction = stick_->Friction(m, c.normal, StickModes(ctx.modes, i), HoldingForce(ctx, patch, i));
        // a stuck point's share is the sensors' and the cone's: the patch's
        // wrench acts as one (below)
        const Vec3 load = c.normal * m.normal + (Stuck(ctx.modes, i) ? Vec3::Zero() : c.friction);
        loads->AddForce(kin, body1_, m.point, load);
        loads->AddForce(kin, body2_, m.point, -load);
      }
    } else {
      Vec3 p;
      delta = Penetration(ctx, i, &p);
      if (ctx.modes[i] != 0.0) c = ApplyPointContact(kin, law_, body1_, body2_, p, n, delta, loads);
    }
    deepest = std::max(deepest, delta);
    if (ctx.modes[i] == 0.0) continue;
    energy += ContactEnergy(law_, delta);
    total_normal += c.normal;
    friction += c.friction;
    if (c.normal > loaded) loaded = c.normal, slip = c.slip;
  }
  if (patch.stuck > 0)
    for (int hold = 0; hold < 3; ++hold) ApplyHold(ctx, patch, hold, ctx.stick_forces[hold], loads);
  sensors[0] = total_normal;
  sensors[1] = deepest;
  sensors[2] = slip;
  sensors[3] = friction.norm();
  sensors[4] = energy;
}

void PointsPlaneContact::ApplyHold(const ElementContext& ctx, const Patch& patch, int hold, double f,
                                   Loads* loads) const {
  if (f == 0.0) return;
  const Kinematics& kin = *ctx.kin;
  if (hold == 2) {
    loads->AddTorque(kin, body1_, f * patch.n);
    loads->AddTorque(kin, body2_, -f * patch.n);
    return;
  }
  ContactStick::ApplyHoldForce(kin, patch.held_motion, hold, f, loads);
}

void PointsPlaneContact::ZeroCrossings(const ElementContext& ctx, std::span<double> values) const {
  const Measured& at = Measure(ctx);
  double deepest = -1e300;
  for (std::size_t i = 0; i < points_.size(); ++i) {
    values[i] = at.depth[i];
    deepest = std::max(deepest, values[i]);
  }
  values[points_.size()] = deepest - law_.max_penetration;
  if (!stick_) return;
  const Patch& patch = MeasurePatch(ctx);
  static const MeasuredPoint kAway;  // a point off the plane: its crossings read no motion
  for (int i = 0; i < num_points(); ++i) {
    const bool touching = ctx.modes[i] != 0.0;
    const MeasuredPoint& point = touching ? Point(ctx, i) : kAway;
    stick_->ZeroCrossings(point.motion, point.normal, touching, StickModes(ctx.modes, i), HoldingForce(ctx, patch, i),
                          values.subspan(num_points() + 1 + ContactStick::kCrossingsPerPoint * i,
                                         ContactStick::kCrossingsPerPoint));
  }
}

std::vector<std::array<double, 2>> PointsPlaneContact::Shares(const ElementContext& ctx, bool* beyond) const {
  const Patch& patch = MeasurePatch(ctx);
  std::vector<std::array<double, 2>> shares(points_.size(), {0.0, 0.0});
  *beyond = false;
  for (int i = 0; i < num_points(); ++i) {
    if (!Stuck(ctx.modes, i)) continue;
    shares[i] = HoldingForce(ctx, patch, i);
    *beyond = *beyond || stick_->Exceeds(Point(ctx, i).normal, shares[i]);
  }
  return shares;
}

void PointsPlaneContact::ReleaseAll(const ElementContext& ctx, const std::vector<std::array<double, 2>>& shares,
                                    std::span<double> modes) const {
  for (int i = 0; i < num_points(); ++i) {
    if (!Stuck(modes, i)) continue;
    ContactStick::OnCrossing(0, Point(ctx, i).motion, shares[i], StickModes(modes, i));
  }
}

bool PointsPlaneContact::UpdateModes(const ElementContext& ctx, std::span<double>, std::span<double> modes) const {
  // the holding forces were solved for the modes coming in (ctx.modes is modes: measured first)
  bool beyond = false;
  const std::vector<std::array<double, 2>> shares = stick_ ? Shares(ctx, &beyond) : std::vector<std::array<double, 2>>{};
  bool changed = false;
  if (beyond) {
    ReleaseAll(ctx, shares, modes);
    changed = true;
  }
  const Measured& at = Measure(ctx);
  for (int i = 0; i < num_points(); ++i) {
    const double delta = at.depth[i];
    // exactly on the plane: in contact when moving into it
    const bool entering = delta == 0 && -Point(ctx, i).motion.slip.dot(Point(ctx, i).motion.normal) > 0;
    const double mode = delta > 0 || entering ? 1.0 : delta < 0 ? 0.0 : modes[i];
    const bool touches = mode != 0.0 && modes[i] == 0.0;
    changed |= mode != modes[i];
    modes[i] = mode;
    if (stick_ && touches) ContactStick::Start(Point(ctx, i).motion, StickModes(modes, i));
  }
  return changed;
}

bool PointsPlaneContact::ModesAtRest(const ElementContext& ctx, std::span<double> state,
                                     std::span<double> modes) const {
  bool changed = UpdateModes(ctx, state, modes);
  if (!stick_) return changed;
  for (int i = 0; i < num_points(); ++i) {
    if (modes[i] == 0.0 || Stuck(modes, i)) continue;
    ContactStick::Start(Point(ctx, i).motion, StickModes(modes, i));
    changed = true;
  }
  return changed;
}

void PointsPlaneContact::OnCrossing(int index, int direction, const ElementContext& ctx, std::span<double>,
                                    std::span<double> modes) const {
  if (index == num_points()) return;  // the bound: a warning only
  if (index < num_points()) {
    modes[index] = direction > 0 ? 1.0 : 0.0;
    if (stick_ && direction > 0) ContactStick::Start(Point(ctx, index).motion, StickModes(modes, index));
    return;
  }
  const int i = (index - num_points() - 1) / ContactStick::kCrossingsPerPoint;
  if (const int which = (index - num_points() - 1) % ContactStick::kCrossingsPerPoint; which != 0) {
    ContactStick::OnCrossing(which, Point(ctx, i).motion, {}, StickModes(modes, i));
    return;
  }
  // one point's share beyond its cone: the contact's stuck points let go together (the others
  // alone would pivot the body about themselves and drag the released point off its slip)
  bool beyond = false;
  ReleaseAll(ctx, Shares(ctx, &beyond), modes);
}

std::string PointsPlaneContact::CrossingName(int index, int direction) const {
  if (index < num_points()) return "point " + std::to_string(index + 1) + (direction > 0 ? " touches" : " leaves");
  if (index == num_points()) return "penetration passes max_penetration";
  const int local = index - num_points() - 1;
  const std::string stick_point = "point " + std::to_string(local / ContactStick::kCrossingsPerPoint + 1);
  return stick_point + " " + ContactStick::CrossingName(local % ContactStick::kCrossingsPerPoint);
}

const PointsPlaneContact::Patch& PointsPlaneContact::MeasurePatch(const ElementContext& ctx) const {
  Measured& at = Measure(ctx);
  bool same = at.patch_valid;
  for (int i = 0; i < num_points(); ++i) {
    const char stuck = Stuck(ctx.modes, i);
    same = same && at.stuck[i] == stuck;
    at.stuck[i] = stuck;
  }
  if (same) return at.patch;
  at.patch_valid = true;
  Patch& patch = at.patch;
  patch = Patch{};
  patch.n = ctx.kin->body_pose[body2_].R * normal_;
  // weights: the normal forces, or equal ones while none presses
  Vec3 weighted = Vec3::Zero();
  for (int i = 0; i < num_points(); ++i) {
    if (!Stuck(ctx.modes, i)) continue;
    const MeasuredPoint& point = Point(ctx, i);
    const double N = std::max(point.normal, 0.0);
    ++patch.stuck;
    patch.normal += N;
    weighted += N * point.motion.point;
    patch.held += point.motion.point;
  }
  if (patch.stuck == 0) return patch;
  patch.held /= patch.stuck;
  patch.held_motion = MeasureContactPoint(*ctx.kin, body1_, body2_, patch.held,
                                          MaterialVelocityAt(*ctx.kin, body1_, patch.held), patch.n, tangent1_,
                                          tangent2_);
  patch.centre = patch.normal > 0.0 ? Vec3(weighted / patch.normal) : patch.held;
  double spread = 0.0;  // of the stuck points about their centroid
  for (int i = 0; i < num_points(); ++i) {
    if (!Stuck(ctx.modes, i)) continue;
    const MeasuredPoint& point = Point(ctx, i);
    const double w = patch.normal > 0.0 ? std::max(point.normal, 0.0) : 1.0;
    const Vec3 r = point.motion.point - patch.centre;
    patch.spin_inertia += w * (r - r.dot(patch.n) * patch.n).squaredNorm();
    spread = std::max(spread, (point.motion.point - patch.held).squaredNorm());
  }
  // round-off of a single pressed point (or of points on one spot): no spin to hold
  if (!(patch.spin_inertia > 1e-12 * std::max(patch.normal, 1.0) * spread)) patch.spin_inertia = 0.0;
  return patch;
}

std::array<double, 2> PointsPlaneContact::Share(const ElementContext& ctx, const Patch& patch, int i, double F1,
                                                double F2, double M) const {
  const MeasuredPoint& point = Point(ctx, i);
  const ContactPointMotion& m = point.motion;
  const bool pressed = patch.normal > 0.0;
  const double w = pressed ? std::max(point.normal, 0.0) : 1.0;
  const double share = w / (pressed ? patch.normal : patch.stuck);
  std::array<double, 2> f = {share * F1, share * F2};
  if (patch.spin_inertia > 0.0) {
    // M about the held point, moved to c: F at the held point turns about c too
    const Vec3 F = F1 * m.t1 + F2 * m.t2;
    const double moment = M + (patch.held - patch.centre).cross(F).dot(patch.n);
    const Vec3 turn = moment * w / patch.spin_inertia * patch.n.cross(m.point - patch.centre);
    f[0] += turn.dot(m.t1);
    f[1] += turn.dot(m.t2);
  }
  return f;
}

bool PointsPlaneContact::StuckExactly(const ElementContext& ctx, int hold) const {
  if (!stick_) return false;
  bool any = false;  // from the modes alone: while every point slides or flies, nothing is measured
  for (int i = 0; i < num_points() && !any; ++i) any = Stuck(ctx.modes, i);
  return any && (hold < 2 || MeasurePatch(ctx).spin_inertia > 0.0);
}

void PointsPlaneContact::ApplyStickForce(const ElementContext& ctx, int hold, double f, Loads* loads) const {
  ApplyHold(ctx, MeasurePatch(ctx), hold, f, loads);
}

double PointsPlaneContact::StickAcceleration(const ElementContext& ctx, int hold, const DynamicsWorkspace& dyn,
                                             std::span<const double>) const {
  const Kinematics& kin = *ctx.kin;
  const Patch& patch = MeasurePatch(ctx);
  if (hold < 2) return ContactStick::HoldAcceleration(*ctx.model, kin, dyn, patch.held_motion, hold);
  // the spin about n, n turning with body 2
  const Vec3 spin = kin.body_omega[body1_] - kin.body_omega[body2_];
  const Vec3 spin_rate =
      AngularAcceleration(*ctx.model, kin, dyn, body1_) - AngularAcceleration(*ctx.model, kin, dyn, body2_);
  return spin_rate.dot(patch.n) + spin.dot(kin.body_omega[body2_].cross(patch.n));
}

double PointsPlaneContact::HoldVelocity(const ElementContext& ctx, int hold) const {
  const Patch& patch = MeasurePatch(ctx);
  if (hold == 2) return (ctx.kin->body_omega[body1_] - ctx.kin->body_omega[body2_]).dot(patch.n);
  const ContactPointMotion& m = patch.held_motion;
  return hold == 0 ? m.s1 : m.s2;
}

void PointsPlaneContact::FollowSlip(const ElementContext& ctx, std::span<double> modes) const {
  for (int i = 0; i < num_points(); ++i)
    if (modes[i] != 0.0) ContactStick::Follow(Point(ctx, i).motion, StickModes(modes, i));
}

std::string PointsPlaneContact::HoldName(int) const { return "contact '" + name() + "'"; }

ElementCoordinate PointsPlaneContact::Coordinate(const std::string& component) const {
  return component.empty() ? ElementCoordinate::Penetration(body1_, body2_, normal_) : ElementCoordinate{};
}

}  // namespace mechflow::mech
