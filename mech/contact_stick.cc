#include "mech/contact_stick.h"

#include <cmath>

#include "mech/dynamics.h"

namespace mechflow::mech {
namespace {

// The slip direction d of a point's modes, global.
Vec3 Direction(const ContactPointMotion& m, std::span<const double> modes) { return modes[1] * m.t1 + modes[2] * m.t2; }

// d := the direction of the point's slip (speed: its size, > 0).
void TurnToSlip(const ContactPointMotion& m, double speed, std::span<double> modes) {
  modes[1] = m.s1 / speed;
  modes[2] = m.s2 / speed;
}

void Stick(std::span<double> modes) {
  modes[0] = ContactStick::kStuck;
  modes[1] = modes[2] = 0.0;
}

// Starts a slip along -f (the way the holding force resisted); a hold with
// no force to speak of (lift-off) keeps the way it last slid, or t_1.
void StartAgainst(std::span<const double> f, std::span<double> modes) {
  modes[0] = ContactStick::kStarting;
  const double size = std::hypot(f[0], f[1]);
  if (size > 0.0) {
    modes[1] = -f[0] / size;
    modes[2] = -f[1] / size;
  } else if (modes[1] == 0.0 && modes[2] == 0.0) {
    modes[1] = 1.0;
  }
}

// At the end of a slip: sticks when the point has (all but) stopped, else
// turns to its new slip direction.
void EndSlip(const ContactPointMotion& m, std::span<double> modes) {
  const double speed = m.speed();
  if (!(speed > ContactStick::kStopSpeed)) return Stick(modes);
  modes[0] = speed > ContactStick::kSteerSpeed ? ContactStick::kSliding : ContactStick::kStarting;
  TurnToSlip(m, speed, modes);
}

}  // namespace

void PlaneTangents(const Vec3& n, Vec3* t1, Vec3* t2) {
  int axis = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(n(i)) < std::abs(n(axis))) axis = i;
  const Vec3 e = Vec3::Unit(axis);
  *t1 = (e - e.dot(n) * n).normalized();
  *t2 = n.cross(*t1);
}

ContactPointMotion MeasureContactPoint(const Kinematics& kin, int body1, int body2, const Vec3& point,
                                       const Vec3& point_rate, const Vec3& normal, const Vec3& tangent1,
                                       const Vec3& tangent2) {
  ContactPointMotion m;
  m.body1 = body1;
  m.body2 = body2;
  m.point = point;
  m.point_rate = point_rate;
  m.normal = normal;
  const Mat3& R2 = kin.body_pose[body2].R;
  m.t1 = R2 * tangent1;
  m.t2 = R2 * tangent2;
  m.slip = MaterialVelocityAt(kin, body1, point) - MaterialVelocityAt(kin, body2, point);
  m.s1 = m.t1.dot(m.slip);
  m.s2 = m.t2.dot(m.slip);
  return m;
}

double ContactStick::Limit(double N) const {
  const double limit = law_.mu_static * N;
  return limit > 1e-9 ? limit : 1e-9;
}

void ContactStick::Start(const ContactPointMotion& m, std::span<double> modes) { EndSlip(m, modes); }

Vec3 ContactStick::Friction(const ContactPointMotion& m, double N, std::span<const double> modes,
                            std::span<const double> f) const {
  if (modes[0] == kStuck) return f[0] * m.t1 + f[1] * m.t2;
  const Vec3 d = Direction(m, modes);
  const Vec3 along = modes[0] == kStarting ? d : Vec3(m.s1 * m.t1 + m.s2 * m.t2 + 2.0 * kEndSpeed * d);
  const double size = along.norm();
  if (!(size > 0.0)) return Vec3::Zero();
  const double stribeck = m.speed() / law_.stribeck_velocity;
  const double mu = law_.mu + (law_.mu_static - law_.mu) * std::exp(-stribeck * stribeck);
  return -mu * N * along / size;
}

void ContactStick::Follow(const ContactPointMotion& m, std::span<double> modes) {
  const double speed = m.speed();
  if (modes[0] == kSliding && speed > 1e3 * kEndSpeed) TurnToSlip(m, speed, modes);
}

void ContactStick::ZeroCrossings(const ContactPointMotion& m, double N, bool touching, std::span<const double> modes,
                                 std::span<const double> f, std::span<double> values) const {
  values[0] = touching && modes[0] == kStuck ? std::hypot(f[0], f[1]) - Limit(N) : -1.0;
  const bool slipping = touching && modes[0] != kStuck;
  values[1] = slipping ? m.s1 * modes[1] + m.s2 * modes[2] + kEndSpeed : 1.0;
  values[2] = slipping && modes[0] == kStarting ? m.speed() - kSteerSpeed : -1.0;
}

void ContactStick::OnCrossing(int which, const ContactPointMotion& m, std::span<const double> f,
                              std::span<double> modes) {
  if (which == 0) {
    StartAgainst(f, modes);
  } else if (which == 1) {
    EndSlip(m, modes);
  } else if (const double speed = m.speed(); speed > 0.0) {
    modes[0] = kSliding;  // at kSteerSpeed, whichever side of it the root lies
    TurnToSlip(m, speed, modes);
  }
}

const char* ContactStick::CrossingName(int which) {
  return which == 0 ? "breaks away" : which == 1 ? "slip ends" : "slip steers";
}

bool ContactStick::Update(double N, std::span<const double> f, std::span<double> modes) const {
  if (modes[0] != kStuck || !Exceeds(N, f)) return false;
  StartAgainst(f, modes);
  return true;
}

double ContactStick::HoldAcceleration(const Model& model, const Kinematics& kin, const DynamicsWorkspace& dyn,
                                      const ContactPointMotion& m, int k) {
  auto material = [&](int body, Vec3* velocity) {
    const Pose& pose = kin.body_pose[body];
    *velocity = MaterialVelocityAt(kin, body, m.point);
    return PointAcceleration(model, kin, dyn, body, pose.R.transpose() * (m.point - pose.p));
  };
  Vec3 v1, v2;
  const Vec3 a1 = material(m.body1, &v1), a2 = material(m.body2, &v2);
  const Vec3& w1 = kin.body_omega[m.body1];
  const Vec3& w2 = kin.body_omega[m.body2];
  // the rate of w = v1(p) - v2(p) as the contact point p moves: each body's
  // material velocity field changes along p's motion relative to that body
  const Vec3 slip_rate = a1 + w1.cross(m.point_rate - v1) - a2 - w2.cross(m.point_rate - v2);
  const Vec3& t = k == 0 ? m.t1 : m.t2;
  return t.dot(slip_rate) + w2.cross(t).dot(m.slip);  // t turns with body 2
}

void ContactStick::ApplyHoldForce(const Kinematics& kin, const ContactPointMotion& m, int k, double f, Loads* loads) {
  const Vec3 force = f * (k == 0 ? m.t1 : m.t2);
  loads->AddForce(kin, m.body1, m.point, force);
  loads->AddForce(kin, m.body2, m.point, -force);
}

}  // namespace mechflow::mech
