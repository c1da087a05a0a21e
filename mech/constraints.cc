#include "mech/constraints.h"

#include <algorithm>
#include <cmath>

#include "mech/dynamics.h"
#include "mech/errors.h"

namespace mechflow::mech {
namespace {

// Rotation error of R (small near the identity): the rotation vector.
Vec3 RotationError(const Mat3& R) {
  const Eigen::AngleAxisd aa(R);
  return aa.axis() * aa.angle();
}

// Global angular part and velocity-at-x part of velocity column(s) of segment a.
struct Column {
  Vec3 angular, linear;
};
Column GlobalColumn(const Kinematics& kin, int segment, const Vec6& local_axis, const Vec3& x) {
  const Pose& pose = kin.pose[segment];
  const Vec3 w = pose.R * local_axis.head<3>();
  return {w, pose.R * local_axis.tail<3>() + w.cross(x - pose.p)};
}

// Classical acceleration of the material point of `segment` at global x, and
// its angular acceleration, from segment accelerations `acc` (segment frames).
void MaterialAcceleration(const Kinematics& kin, const std::vector<Vec6>& acc, int segment, const Vec3& x,
                          Vec3* alpha, Vec3* a) {
  if (segment == kGround) {
    alpha->setZero();
    a->setZero();
    return;
  }
  const Pose& pose = kin.pose[segment];
  const Vec6& v = kin.velocity[segment];
  const Vec3 r = pose.R.transpose() * (x - pose.p);
  const Vec3 w = v.head<3>();
  const Vec3 vel = v.tail<3>() + w.cross(r);
  *alpha = pose.R * acc[segment].head<3>();
  *a = pose.R * (acc[segment].tail<3>() + acc[segment].head<3>().cross(r) + w.cross(vel));
}

Vec3 MaterialVelocity(const Kinematics& kin, int segment, const Vec3& x, Vec3* omega) {
  if (segment == kGround) {
    omega->setZero();
    return Vec3::Zero();
  }
  const Pose& pose = kin.pose[segment];
  const Vec6& v = kin.velocity[segment];
  *omega = pose.R * v.head<3>();
  return pose.R * (v.tail<3>() + v.head<3>().cross(pose.R.transpose() * (x - pose.p)));
}

}  // namespace

namespace {

// A unit vector perpendicular to the unit vector a.
Vec3 Perpendicular(const Vec3& a) {
  const Vec3 helper = std::abs(a.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  return a.cross(helper).cross(a).normalized();
}

Mat3 ShaftFrame(const Vec3& axis, const Vec3& reference) {
  Mat3 Q;
  const Vec3 b = (reference - reference.dot(axis) * axis).normalized();
  Q << b, axis.cross(b), axis;
  return Q;
}

}  // namespace

Constraints::Constraints(const Model& model, std::span<const double> q0) {
  Kinematics kin(model);
  const std::vector<double> v0(model.nv(), 0.0);
  UpdateKinematics(model, 0.0, q0, v0, &kin);
  for (int j = 0; j < static_cast<int>(model.joints().size()); ++j) {
    const Joint& joint = model.joints()[j];
    if (!joint.is_cut) continue;
    Cut cut;
    cut.joint = j;
    cut.convel = joint.convel;
    cut.row = size_;
    cut.rows = joint.convel ? 4 : 6;
    if (joint.convel) {
      // References: given, or chosen so that the initial relative rotation has
      // no twist (shaft 2's reference is shaft 1's carried by the swing).
      const Mat3& A1 = kin.body_pose[joint.body1].R;
      const Mat3& A2 = kin.body_pose[joint.body2].R;
      const Vec3 b1 = joint.cv_reference1.norm() > 0 ? joint.cv_reference1 : Perpendicular(joint.cv_axis1);
      Vec3 b2 = joint.cv_reference2;
      if (!(b2.norm() > 0)) {
        const Eigen::Quaterniond swing = Eigen::Quaterniond::FromTwoVectors(A1 * joint.cv_axis1, A2 * joint.cv_axis2);
        b2 = A2.transpose() * (swing * (A1 * b1));
      }
      cut.Q1 = ShaftFrame(joint.cv_axis1, b1);
      cut.Q2 = ShaftFrame(joint.cv_axis2, b2);
    }
    cuts_.push_back(cut);
    cut_joints_.push_back(j);
    size_ += cut.rows;
  }
}

Pose Constraints::FrameG(const Model& model, const Kinematics& kin, int k) const {
  const Joint& joint = model.joints()[cuts_[k].joint];
  if (joint.last_segment == kGround) return joint.end_offset;
  return kin.pose[joint.last_segment] * joint.end_offset;
}

Pose Constraints::FrameB(const Model& model, const Kinematics& kin, int k) const {
  const Joint& joint = model.joints()[cuts_[k].joint];
  return kin.body_pose[joint.body2] * joint.body2_attachment;
}

double Constraints::Twist(const Model& model, const Kinematics& kin, const Cut& cut) const {
  const Joint& joint = model.joints()[cut.joint];
  const Mat3 J1 = kin.body_pose[joint.body1].R * cut.Q1, J2 = kin.body_pose[joint.body2].R * cut.Q2;
  return J1.col(1).dot(J2.col(0)) - J1.col(0).dot(J2.col(1));
}

Vec3 Constraints::TwistGradient(const Model& model, const Kinematics& kin, const Cut& cut) const {
  const Joint& joint = model.joints()[cut.joint];
  const Mat3 J1 = kin.body_pose[joint.body1].R * cut.Q1, J2 = kin.body_pose[joint.body2].R * cut.Q2;
  // d/dt (J1_i . J2_j) = (w2 - w1) . (J2_j x J1_i)
  return J2.col(0).cross(J1.col(1)) - J2.col(1).cross(J1.col(0));
}

void Constraints::Residual(const Model& model, const Kinematics& kin, Eigen::VectorXd* phi) const {
  phi->resize(size());
  for (int k = 0; k < static_cast<int>(cuts_.size()); ++k) {
    const Cut& cut = cuts_[k];
    const Joint& joint = model.joints()[cut.joint];
    if (cut.convel) {
      phi->segment<3>(cut.row) =
          PointPosition(kin, joint.body2, joint.cv_point2) - PointPosition(kin, joint.body1, joint.cv_point1);
      (*phi)(cut.row + 3) = Twist(model, kin, cut);
      continue;
    }
    const Pose G = FrameG(model, kin, k), B = FrameB(model, kin, k);
    phi->segment<3>(cut.row) = RotationError(G.R.transpose() * B.R);
    phi->segment<3>(cut.row + 3) = G.R.transpose() * (B.p - G.p);
  }
}

void Constraints::Jacobian(const Model& model, const Kinematics& kin, Eigen::MatrixXd* J) const {
  J->setZero(size(), model.nv());
  const auto& segments = model.segments();
  for (int k = 0; k < static_cast<int>(cuts_.size()); ++k) {
    const Cut& cut = cuts_[k];
    const Joint& joint = model.joints()[cut.joint];
    // Side B (body 2) enters with +, side A (ghost end or body 1) with -.
    const int side_segment[2] = {model.bodies()[joint.body2].segment,
                                 cut.convel ? model.bodies()[joint.body1].segment : joint.last_segment};
    Vec3 side_point[2];
    Mat3 rows_angular = Mat3::Identity();  // global angular velocity -> the weld's angular rows
    if (cut.convel) {
      side_point[0] = PointPosition(kin, joint.body2, joint.cv_point2);
      side_point[1] = PointPosition(kin, joint.body1, joint.cv_point1);
    } else {
      const Pose G = FrameG(model, kin, k), B = FrameB(model, kin, k);
      side_point[0] = side_point[1] = B.p;
      rows_angular = G.R.transpose();
    }
    const Vec3 g = cut.convel ? TwistGradient(model, kin, cut) : Vec3::Zero();
    for (int side = 0; side < 2; ++side) {
      const int sb = side_segment[side];
      if (sb == kGround) continue;
      const double sign = side == 0 ? 1.0 : -1.0;
      // the segments on the path from the root to this side's segment
      for (int a = sb; a != kGround; a = segments[a].parent) {
        const Segment& seg = segments[a];
        if (seg.drive != SegmentDrive::kDof) continue;
        const int ncols = seg.motion == SegmentMotion::kFree ? 6 : 1;
        for (int c = 0; c < ncols; ++c) {
          const Vec6 axis = ncols == 6 ? Vec6(Vec6::Unit(c)) : kin.axis[a];
          const Column col = GlobalColumn(kin, a, axis, side_point[side]);
          auto column = J->col(seg.v_index + c);
          if (cut.convel) {
            column.segment<3>(cut.row) += sign * col.linear;
            column(cut.row + 3) += sign * g.dot(col.angular);
          } else {
            column.segment<3>(cut.row) += sign * (rows_angular * col.angular);
            column.segment<3>(cut.row + 3) += sign * (rows_angular * col.linear);
          }
        }
      }
    }
  }
}

void Constraints::VelocityResidual(const Model& model, const Kinematics& kin, Eigen::VectorXd* psi) const {
  psi->resize(size());
  for (int k = 0; k < static_cast<int>(cuts_.size()); ++k) {
    const Cut& cut = cuts_[k];
    const Joint& joint = model.joints()[cut.joint];
    if (cut.convel) {
      const Vec3 p1 = PointPosition(kin, joint.body1, joint.cv_point1);
      const Vec3 p2 = PointPosition(kin, joint.body2, joint.cv_point2);
      psi->segment<3>(cut.row) = MaterialVelocityAt(kin, joint.body2, p2) - MaterialVelocityAt(kin, joint.body1, p1);
      (*psi)(cut.row + 3) =
          TwistGradient(model, kin, cut).dot(kin.body_omega[joint.body2] - kin.body_omega[joint.body1]);
      continue;
    }
    const Pose G = FrameG(model, kin, k), B = FrameB(model, kin, k);
    Vec3 wb, wg;
    const Vec3 vb = MaterialVelocity(kin, model.bodies()[joint.body2].segment, B.p, &wb);
    const Vec3 vg = MaterialVelocity(kin, joint.last_segment, B.p, &wg);
    psi->segment<3>(cut.row) = G.R.transpose() * (wb - wg);
    psi->segment<3>(cut.row + 3) = G.R.transpose() * (vb - vg);
  }
}

void Constraints::AccelerationBias(const Model& model, const Kinematics& kin, std::vector<Vec6>* acc,
                                   Eigen::VectorXd* bias) const {
  const auto& segments = model.segments();
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const int p = segments[i].parent;
    (*acc)[i] = (p == kGround ? Vec6(Vec6::Zero()) : kin.X[i].Motion((*acc)[p])) + kin.bias[i];
  }
  bias->resize(size());
  for (int k = 0; k < static_cast<int>(cuts_.size()); ++k) {
    const Cut& cut = cuts_[k];
    const Joint& joint = model.joints()[cut.joint];
    const int sb = model.bodies()[joint.body2].segment;
    if (cut.convel) {
      const int sa = model.bodies()[joint.body1].segment;
      const Vec3 p1 = PointPosition(kin, joint.body1, joint.cv_point1);
      const Vec3 p2 = PointPosition(kin, joint.body2, joint.cv_point2);
      Vec3 alpha_b, a_b, alpha_a, a_a;
      MaterialAcceleration(kin, *acc, sb, p2, &alpha_b, &a_b);
      MaterialAcceleration(kin, *acc, sa, p1, &alpha_a, &a_a);
      bias->segment<3>(cut.row) = a_b - a_a;
      // d/dt [g . w] = g' . w + g . alpha, g' from the columns turning with their bodies.
      const Vec3& w1 = kin.body_omega[joint.body1];
      const Vec3& w2 = kin.body_omega[joint.body2];
      const Mat3 J1 = kin.body_pose[joint.body1].R * cut.Q1, J2 = kin.body_pose[joint.body2].R * cut.Q2;
      const Vec3 g = TwistGradient(model, kin, cut);
      const Vec3 gdot = w2.cross(J2.col(0)).cross(J1.col(1)) + J2.col(0).cross(w1.cross(J1.col(1))) -
                        w2.cross(J2.col(1)).cross(J1.col(0)) - J2.col(1).cross(w1.cross(J1.col(0)));
      (*bias)(cut.row + 3) = gdot.dot(w2 - w1) + g.dot(alpha_b - alpha_a);
      continue;
    }
    const Pose G = FrameG(model, kin, k), B = FrameB(model, kin, k);
    Vec3 alpha_b, a_b, alpha_g, a_g;
    MaterialAcceleration(kin, *acc, sb, B.p, &alpha_b, &a_b);
    MaterialAcceleration(kin, *acc, joint.last_segment, B.p, &alpha_g, &a_g);
    bias->segment<3>(cut.row) = G.R.transpose() * (alpha_b - alpha_g);
    bias->segment<3>(cut.row + 3) = G.R.transpose() * (a_b - a_g);
  }
}

Constraints::Load Constraints::LoadOf(const Model& model, const Kinematics& kin, const Eigen::VectorXd& lambda,
                                      int k) const {
  const Cut& cut = cuts_[k];
  const Joint& joint = model.joints()[cut.joint];
  Load load;
  load.segment_b = model.bodies()[joint.body2].segment;
  if (cut.convel) {
    load.segment_a = model.bodies()[joint.body1].segment;
    load.point_b = PointPosition(kin, joint.body2, joint.cv_point2);
    load.point_a = PointPosition(kin, joint.body1, joint.cv_point1);
    load.force = lambda.segment<3>(cut.row);
    load.torque = TwistGradient(model, kin, cut) * lambda(cut.row + 3);
    return load;
  }
  const Pose G = FrameG(model, kin, k);
  load.segment_a = joint.last_segment;
  load.point_b = load.point_a = FrameB(model, kin, k).p;
  load.torque = G.R * lambda.segment<3>(cut.row);
  load.force = G.R * lambda.segment<3>(cut.row + 3);
  return load;
}

}  // namespace mechflow::mech
