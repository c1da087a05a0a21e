#include "mech/bushing.h"

namespace mechflow::mech {

Bushing::Bushing(std::string name, std::string origin, int body1, Vec3 point1, int body2, Vec3 point2,
                 BushingParameters parameters, const Kinematics& initial)
    : ForceElement(std::move(name), std::move(origin)),
      body1_(body1),
      body2_(body2),
      point1_(point1),
      point2_(point2),
      p_(parameters),
      initial_relative_(initial.body_pose[body1].R.transpose() * initial.body_pose[body2].R) {
  DeclareBodies({body1_, body2_});
  for (const char* s : {"fx", "fy", "fz", "mx", "my", "mz", "dx", "dy", "dz", "ax", "ay", "az"}) DeclareSensor(s);
}

Vec3 BushingCoincidentPoint(const Kinematics& kin, int body1, const Vec3& point1, int body2) {
  return kin.body_pose[body2].Inverse() * PointPosition(kin, body1, point1);
}

void Bushing::Evaluate(const ElementContext& ctx, Loads* loads, std::span<double>, std::span<double> sensors) const {
  const Kinematics& kin = *ctx.kin;
  const Mat3& A1 = kin.body_pose[body1_].R;
  const Vec3 p1 = PointPosition(kin, body1_, point1_), p2 = PointPosition(kin, body2_, point2_);
  const Vec3 w1 = A1.transpose() * kin.body_omega[body1_];
  const Vec3 delta = A1.transpose() * (p2 - p1);
  const Vec3 delta_rate =
      A1.transpose() * (PointVelocity(kin, body2_, point2_) - PointVelocity(kin, body1_, point1_)) - w1.cross(delta);
  const Mat3 R = A1.transpose() * kin.body_pose[body2_].R * initial_relative_.transpose();
  const Vec3 theta = 0.5 * Vec3(R(2, 1) - R(1, 2), R(0, 2) - R(2, 0), R(1, 0) - R(0, 1));
  const Vec3 w_rel = A1.transpose() * (kin.body_omega[body2_] - kin.body_omega[body1_]);
  Vec3 f, m;
  for (int i = 0; i < 3; ++i) {
    f(i) = -(p_.stiffness[i] * delta(i) + p_.damping[i] * delta_rate(i)) + p_.preload_force(i);
    m(i) = -(p_.angular_stiffness[i] * theta(i) + p_.angular_damping[i] * w_rel(i)) + p_.preload_moment(i);
  }
  loads->AddForce(kin, body2_, p2, A1 * f);
  loads->AddTorque(kin, body2_, A1 * m);
  loads->AddForce(kin, body1_, p2, -(A1 * f));  // at p2: see the header
  loads->AddTorque(kin, body1_, -(A1 * m));
  for (int i = 0; i < 3; ++i) {
    sensors[i] = f(i);
    sensors[3 + i] = m(i);
    sensors[6 + i] = delta(i);
    sensors[9 + i] = theta(i);
  }
}

ElementCoordinate Bushing::Coordinate(const std::string& component) const {
  // dx dy dz: body 2 moved along body 1's axis; ax ay az: turned about it
  ElementCoordinate c;
  const std::string names = "xyz";
  if (component.size() != 2 || (component[0] != 'd' && component[0] != 'a') ||
      names.find(component[1]) == std::string::npos)
    return c;
  const int i = static_cast<int>(names.find(component[1]));
  c.kind = component[0] == 'd' ? ElementCoordinate::Kind::kTranslation : ElementCoordinate::Kind::kRotation;
  c.body1 = body1_;
  c.body2 = body2_;
  c.point1 = point1_;
  c.point2 = point2_;
  c.axis = Vec3::Unit(i);
  c.force_sensor = component[0] == 'd' ? i : 3 + i;  // f or m on body 2, body 1's axes
  c.coordinate_sensor = c.force_sensor + 6;          // delta or theta
  return c;
}

}  // namespace mechflow::mech
