#include "mech/bipolar_force.h"

#include <cmath>
#include <sstream>

#include "mech/errors.h"

namespace mechflow::mech {
namespace {

// True when d lies on a coordinate axis (one non-zero component).
bool AlongAnAxis(const Vec3& d) { return (d.x() != 0.0) + (d.y() != 0.0) + (d.z() != 0.0) == 1; }

}  // namespace

BipolarForce::BipolarForce(std::string name, std::string origin, int body1, Vec3 point1, int body2, Vec3 point2,
                           std::unique_ptr<ForceLaw> law)
    : ForceElement(std::move(name), std::move(origin)),
      body1_(body1),
      body2_(body2),
      point1_(point1),
      point2_(point2),
      law_(std::move(law)) {
  DeclareBodies({body1_, body2_});
  DeclareDependsOnInputs(law_->depends_on_inputs());
  DeclareSensor("force");
  DeclareSensor("length");
  DeclareSensor("rate");
  if (law_->has_energy()) DeclareSensor("energy");  // stored in its spring
}

double BipolarLength(const Kinematics& kin, int body1, const Vec3& point1, int body2, const Vec3& point2) {
  return (PointPosition(kin, body2, point2) - PointPosition(kin, body1, point1)).norm();
}

BipolarGeometry MeasureBipolar(const Kinematics& kin, int body1, const Vec3& point1, int body2, const Vec3& point2) {
  // A point at its body's origin (the usual case: chains of masses) is the
  // body's position and moves with its velocity: nothing to rotate. The same
  // numbers, up to the sign of a zero.
  const bool origin1 = point1 == Vec3::Zero(), origin2 = point2 == Vec3::Zero();
  const Vec3 pa = origin1 ? kin.body_pose[body1].p : PointPosition(kin, body1, point1);
  const Vec3 pb = origin2 ? kin.body_pose[body2].p : PointPosition(kin, body2, point2);
  const Vec3 d = pb - pa;
  // Along a coordinate axis (a line of masses along x, say) the length is
  // that component's magnitude: the same numbers without the square root and
  // the divisions (sqrt(a^2) = |a| and (+-0)/x = +-0 in IEEE arithmetic).
  // Locals, not the result's fields, until the end: a field written by index
  // and read back as a vector stalls the store forwarding.
  double x;
  Vec3 u;
  if (AlongAnAxis(d)) {
    const double along = d.x() + d.y() + d.z();  // the non-zero component, exactly (the others are zeros)
    const double s = along > 0.0 ? 1.0 : -1.0;
    x = std::abs(along);
    u = Vec3(d.x() != 0.0 ? s : d.x(), d.y() != 0.0 ? s : d.y(), d.z() != 0.0 ? s : d.z());
  } else {
    x = d.norm();
    u = x > 0.0 ? Vec3(d / x) : Vec3(Vec3::Zero());
  }
  const Vec3 va = origin1 ? kin.body_velocity[body1] : PointVelocity(kin, body1, point1);
  const Vec3 vb = origin2 ? kin.body_velocity[body2] : PointVelocity(kin, body2, point2);
  return {pa, pb, u, x, (vb - va).dot(u)};
}

void BipolarForce::Evaluate(const ElementContext& ctx, Loads* loads, std::span<double>,
                            std::span<double> sensors) const {
  const Kinematics& kin = *ctx.kin;
  const auto [pa, pb, u, x, v] = MeasureBipolar(kin, body1_, point1_, body2_, point2_);
  const double f = law_->Force(x, v, ctx);
  if (x == 0.0 && f != 0.0) {
    std::ostringstream out;
    out << "force '" << name() << "': zero length with a non-zero force " << f << " at t = " << ctx.t
        << " (no direction to apply it)";
    throw SimulationError(out.str());
  }
  loads->AddForce(kin, body2_, pb, f * u);
  loads->AddForce(kin, body1_, pa, -f * u);
  sensors[0] = f;
  sensors[1] = x;
  sensors[2] = v;
  if (law_->has_energy()) sensors[3] = law_->Energy(x, ctx);
}

ElementCoordinate BipolarForce::Coordinate(const std::string& component) const {
  return component.empty() ? ElementCoordinate::Line(body1_, point1_, body2_, point2_) : ElementCoordinate{};
}

}  // namespace mechflow::mech
