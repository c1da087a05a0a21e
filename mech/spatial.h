#pragma once
// Small 3-D and spatial (6-D) algebra shared by the mechanics.
//
// Conventions (docs/ELEMENTS.md 0.1): a rotation matrix maps frame-local
// components to parent (ultimately global) components; a Pose places a child
// frame in its parent: x_parent = R * x_child + p. Spatial vectors follow
// Featherstone: motion [angular; linear], force [moment; force], both in one
// frame's axes and about that frame's origin.

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace mechflow::mech {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

inline Mat3 Skew(const Vec3& a) {
  Mat3 s;
  s << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return s;
}

// Rodrigues rotation by `angle` [rad] about the unit vector `axis`.
inline Mat3 AxisRotation(const Vec3& axis, double angle) {
  return Eigen::AngleAxisd(angle, axis).toRotationMatrix();
}

struct Pose {
  Mat3 R = Mat3::Identity();
  Vec3 p = Vec3::Zero();

  static Pose Translation(const Vec3& p) { return {Mat3::Identity(), p}; }
  static Pose Rotation(const Mat3& R) { return {R, Vec3::Zero()}; }
  Vec3 operator*(const Vec3& x) const { return R * x + p; }
  Pose operator*(const Pose& child) const { return {R * child.R, R * child.p + p}; }
  Pose Inverse() const { return {R.transpose(), -(R.transpose() * p)}; }
};

// Plücker transform from a parent frame to a child frame placed by `pose`
// (the child in the parent). Stored as (E = R^T, r = p) and applied without
// forming 6x6 matrices.
struct SpatialTransform {
  Mat3 E = Mat3::Identity();  // parent -> child rotation
  Vec3 r = Vec3::Zero();      // child origin in parent components

  static SpatialTransform FromPose(const Pose& pose) { return {pose.R.transpose(), pose.p}; }

  // Motion vector from parent to child coordinates.
  Vec6 Motion(const Vec6& m) const {
    Vec6 out;
    out.head<3>() = E * m.head<3>();
    out.tail<3>() = E * (m.tail<3>() - r.cross(m.head<3>()));
    return out;
  }
  // Force vector from child to parent coordinates (the transpose map).
  Vec6 ForceToParent(const Vec6& f) const {
    Vec6 out;
    out.tail<3>() = E.transpose() * f.tail<3>();
    out.head<3>() = E.transpose() * f.head<3>() + r.cross(out.tail<3>());
    return out;
  }
  // Motion vector from child to parent coordinates.
  Vec6 MotionToParent(const Vec6& m) const {
    Vec6 out;
    out.head<3>() = E.transpose() * m.head<3>();
    out.tail<3>() = E.transpose() * m.tail<3>() + r.cross(out.head<3>());
    return out;
  }
  // The 6x6 matrix of Motion().
  Mat6 Matrix() const {
    Mat6 X;
    X.topLeftCorner<3, 3>() = E;
    X.topRightCorner<3, 3>().setZero();
    X.bottomLeftCorner<3, 3>() = -E * Skew(r);
    X.bottomRightCorner<3, 3>() = E;
    return X;
  }
};

// Spatial cross products: motion x motion, and motion x* force.
inline Vec6 CrossMotion(const Vec6& v, const Vec6& m) {
  Vec6 out;
  out.head<3>() = v.head<3>().cross(m.head<3>());
  out.tail<3>() = v.head<3>().cross(m.tail<3>()) + v.tail<3>().cross(m.head<3>());
  return out;
}
inline Vec6 CrossForce(const Vec6& v, const Vec6& f) {
  Vec6 out;
  out.head<3>() = v.head<3>().cross(f.head<3>()) + v.tail<3>().cross(f.tail<3>());
  out.tail<3>() = v.head<3>().cross(f.tail<3>());
  return out;
}

// Spatial inertia about a frame's origin of a body with mass m, centre of mass
// c and rotational inertia Ic about the centre of mass, all in that frame.
inline Mat6 SpatialInertia(double m, const Vec3& c, const Mat3& Ic) {
  const Mat3 C = Skew(c);
  Mat6 I;
  I.topLeftCorner<3, 3>() = Ic + m * C * C.transpose();
  I.topRightCorner<3, 3>() = m * C;
  I.bottomLeftCorner<3, 3>() = m * C.transpose();
  I.bottomRightCorner<3, 3>() = m * Mat3::Identity();
  return I;
}

}  // namespace mechflow::mech
