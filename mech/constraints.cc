#include "mech/constraints.h"

#include <cmath>

#include "mech/dynamics.h"

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

Constraints::Constraints(const Model& model) {
  for (int j = 0; j < static_cast<int>(model.joints().size()); ++j)
    if (model.joints()[j].is_cut) cut_joints_.push_back(j);
  const auto& segments = model.segments();
  is_ancestor_.assign(segments.size(), std::vector<bool>(segments.size(), false));
  for (std::size_t s = 0; s < segments.size(); ++s)
    for (int a = static_cast<int>(s); a != kGround; a = segments[a].parent) is_ancestor_[s][a] = true;
}

Pose Constraints::FrameG(const Model& model, const Kinematics& kin, int k) const {
  const Joint& joint = model.joints()[cut_joints_[k]];
  if (joint.last_segment == kGround) return joint.end_offset;
  return kin.pose[joint.last_segment] * joint.end_offset;
}

Pose Constraints::FrameB(const Model& model, const Kinematics& kin, int k) const {
  const Joint& joint = model.joints()[cut_joints_[k]];
  return kin.body_pose[joint.body2] * joint.body2_attachment;
}

void Constraints::Residual(const Model& model, const Kinematics& kin, Eigen::VectorXd* phi) const {
  phi->resize(size());
  for (int k = 0; k < static_cast<int>(cut_joints_.size()); ++k) {
    const Pose G = FrameG(model, kin, k), B = FrameB(model, kin, k);
    phi->segment<3>(6 * k) = RotationError(G.R.transpose() * B.R);
    phi->segment<3>(6 * k + 3) = G.R.transpose() * (B.p - G.p);
  }
}

void Constraints::Jacobian(const Model& model, const Kinematics& kin, Eigen::MatrixXd* J) const {
  J->setZero(size(), model.nv());
  const auto& segments = model.segments();
  for (int k = 0; k < static_cast<int>(cut_joints_.size()); ++k) {
    const Joint& joint = model.joints()[cut_joints_[k]];
    const Pose G = FrameG(model, kin, k), B = FrameB(model, kin, k);
    const int sb = model.bodies()[joint.body2].segment, sg = joint.last_segment;
    const Mat3 Rt = G.R.transpose();
    for (int a = 0; a < static_cast<int>(segments.size()); ++a) {
      const Segment& seg = segments[a];
      if (seg.drive != SegmentDrive::kDof) continue;
      const double sign = (sb != kGround && is_ancestor_[sb][a] ? 1.0 : 0.0) -
                          (sg != kGround && is_ancestor_[sg][a] ? 1.0 : 0.0);
      if (sign == 0.0) continue;
      const int ncols = seg.motion == SegmentMotion::kFree ? 6 : 1;
      for (int c = 0; c < ncols; ++c) {
        const Vec6 axis = ncols == 6 ? Vec6(Vec6::Unit(c)) : kin.axis[a];
        const Column col = GlobalColumn(kin, a, axis, B.p);
        J->block<3, 1>(6 * k, seg.v_index + c) = sign * (Rt * col.angular);
        J->block<3, 1>(6 * k + 3, seg.v_index + c) = sign * (Rt * col.linear);
      }
    }
  }
}

void Constraints::VelocityResidual(const Model& model, const Kinematics& kin, Eigen::VectorXd* psi) const {
  psi->resize(size());
  for (int k = 0; k < static_cast<int>(cut_joints_.size()); ++k) {
    const Joint& joint = model.joints()[cut_joints_[k]];
    const Pose G = FrameG(model, kin, k), B = FrameB(model, kin, k);
    Vec3 wb, wg;
    const Vec3 vb = MaterialVelocity(kin, model.bodies()[joint.body2].segment, B.p, &wb);
    const Vec3 vg = MaterialVelocity(kin, joint.last_segment, B.p, &wg);
    psi->segment<3>(6 * k) = G.R.transpose() * (wb - wg);
    psi->segment<3>(6 * k + 3) = G.R.transpose() * (vb - vg);
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
  for (int k = 0; k < static_cast<int>(cut_joints_.size()); ++k) {
    const Joint& joint = model.joints()[cut_joints_[k]];
    const Pose G = FrameG(model, kin, k), B = FrameB(model, kin, k);
    Vec3 alpha_b, a_b, alpha_g, a_g;
    MaterialAcceleration(kin, *acc, model.bodies()[joint.body2].segment, B.p, &alpha_b, &a_b);
    MaterialAcceleration(kin, *acc, joint.last_segment, B.p, &alpha_g, &a_g);
    bias->segment<3>(6 * k) = G.R.transpose() * (alpha_b - alpha_g);
    bias->segment<3>(6 * k + 3) = G.R.transpose() * (a_b - a_g);
  }
}

ConstraintWorkspace::ConstraintWorkspace(const Model& model, const Constraints& constraints) {
  const int m = constraints.size(), n = model.nv();
  M.setZero(n, n);
  J.setZero(m, n);
  kkt.setZero(n + m, n + m);
  phi.setZero(m);
  psi.setZero(m);
  bias.setZero(m);
  rhs.setZero(n + m);
  solution.setZero(n + m);
  lambda.setZero(m);
  kkt_solver = Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(n + m, n + m);
  j_solver = Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(m, n);
  scratch.assign(model.segments().size(), Vec6::Zero());
  loads.assign(model.segments().size(), Vec6::Zero());
  h.assign(n, 0.0);
  zero.assign(n, 0.0);
}

namespace {

// q += dv, with quaternion blocks advanced by the rotation vector in body axes.
void AddVelocityStep(const Model& model, std::span<double> q, const Eigen::VectorXd& dv) {
  for (const Dof& dof : model.dofs()) q[dof.q_index] += dv(dof.v_index);
  for (const Segment& seg : model.segments()) {
    if (seg.motion != SegmentMotion::kFree) continue;
    const int iq = seg.q_index, iv = seg.v_index;
    Eigen::Quaterniond quat(q[iq + 3], q[iq + 4], q[iq + 5], q[iq + 6]);
    const Vec3 dtheta = dv.segment<3>(iv);
    const Vec3 dp = quat.normalized().toRotationMatrix() * dv.segment<3>(iv + 3);
    const double angle = dtheta.norm();
    if (angle > 0.0) quat = quat * Eigen::Quaterniond(Eigen::AngleAxisd(angle, dtheta / angle));
    quat.normalize();
    for (int c = 0; c < 3; ++c) q[iq + c] += dp(c);
    q[iq + 3] = quat.w();
    q[iq + 4] = quat.x();
    q[iq + 5] = quat.y();
    q[iq + 6] = quat.z();
  }
}

}  // namespace

double ProjectPositions(const Model& model, const Constraints& constraints, double t, std::span<double> q,
                        std::span<const double> v, double tolerance, int max_iterations, Kinematics* kin,
                        ConstraintWorkspace* ws) {
  double norm = 0.0;
  for (int it = 0;; ++it) {
    UpdateKinematics(model, t, q, v, kin);
    constraints.Residual(model, *kin, &ws->phi);
    norm = ws->phi.size() ? ws->phi.lpNorm<Eigen::Infinity>() : 0.0;
    if (norm <= tolerance || it >= max_iterations || !std::isfinite(norm)) break;
    constraints.Jacobian(model, *kin, &ws->J);
    ws->j_solver.compute(ws->J);
    ws->solution.head(model.nv()) = ws->j_solver.solve(ws->phi);
    AddVelocityStep(model, q, -ws->solution.head(model.nv()));
  }
  return norm;
}

void ProjectVelocities(const Model& model, const Constraints& constraints, double t, std::span<const double> q,
                       std::span<double> v, Kinematics* kin, ConstraintWorkspace* ws) {
  UpdateKinematics(model, t, q, v, kin);
  constraints.VelocityResidual(model, *kin, &ws->psi);
  constraints.Jacobian(model, *kin, &ws->J);
  ws->j_solver.compute(ws->J);
  ws->solution.head(model.nv()) = ws->j_solver.solve(ws->psi);
  for (int i = 0; i < model.nv(); ++i) v[i] -= ws->solution(i);
}

}  // namespace mechflow::mech
