#include "mech/dynamics.h"

#include <cmath>
#include <sstream>

#include <Eigen/Cholesky>

#include "mech/errors.h"
#include "mech/sliding_structure.h"

namespace mechflow::mech {
namespace {

// Ground acceleration that stands in for gravity, in the segment's parent frame.
Vec6 ParentAcceleration(const Model& model, const Kinematics& kin, const DynamicsWorkspace& ws, int i) {
  const Segment& seg = model.segments()[i];
  if (seg.parent != kGround) return kin.X[i].Motion(ws.acceleration[seg.parent]);
  Vec6 a0;
  a0 << Vec3::Zero(), -model.gravity();
  return kin.X[i].Motion(a0);
}

Mat6 TransformInertiaToParent(const SpatialTransform& X, const Mat6& I) {
  const Mat6 Xm = X.Matrix();
  return Xm.transpose() * I * Xm;
}

[[noreturn]] void ThrowSingular(const Model& model, const Kinematics& kin, int segment) {
  const Segment& seg = model.segments()[segment];
  std::ostringstream out;
  out << "singular mass matrix at t = " << kin.time << ": nothing beyond joint '"
      << model.joints()[seg.joint].name << "' has inertia about its "
      << (seg.motion == SegmentMotion::kPrismatic ? "translation" : "rotation") << " axis";
  throw SimulationError(out.str());
}

}  // namespace

DynamicsWorkspace::DynamicsWorkspace(const Model& model) {
  const std::size_t n = model.segments().size();
  articulated_inertia.assign(n, Mat6::Zero());
  articulated_bias.assign(n, Vec6::Zero());
  U.assign(n, Vec6::Zero());
  D.assign(n, 0.0);
  u.assign(n, 0.0);
  U6.assign(n, Mat6::Zero());
  D6.resize(n);
  u6.assign(n, Vec6::Zero());
  acceleration.assign(n, Vec6::Zero());
  force.assign(n, Vec6::Zero());
  composite.assign(n, Mat6::Zero());
  if (model.sliding()) {
    sliding_field.assign(n, Vec3::Zero());
    sliding_force.assign(n, Vec3::Zero());
  }
}

namespace {

// ForwardDynamics of a sliding model: M_ii v_i' = tau_i + a_i . (the force
// on everything coordinate i carries), gravity and the time-driven
// accelerations included as the bodies' field (mech/sliding_structure.h).
void SlidingDynamics(const Model& model, const Kinematics& kin, std::span<const double> tau,
                     std::span<const Vec6> external, std::span<double> vdot, DynamicsWorkspace* ws) {
  const SlidingStructure& sliding = *model.sliding();
  const auto& segments = sliding.slides;  // packed: the model's records are large
  const int n = static_cast<int>(segments.size());
  for (int i = 0; i < n; ++i) {
    const SlidingStructure::Slide& seg = segments[i];
    Vec3 field = seg.parent == kGround ? model.gravity() : ws->sliding_field[seg.parent];
    if (seg.drive == SegmentDrive::kTime) field -= sliding.axis[i] * kin.prescribed[i].acceleration;
    ws->sliding_field[i] = field;
    ws->sliding_force[i] = kin.pose[i].R * external[i].tail<3>() + sliding.carried_mass[i] * field;
  }
  for (int i = n - 1; i >= 0; --i) {  // children come after their parents
    const SlidingStructure::Slide& seg = segments[i];
    if (seg.drive == SegmentDrive::kDof)
      vdot[seg.v_index] =
          (tau[seg.v_index] + sliding.axis[i].dot(ws->sliding_force[i])) / sliding.coordinate_mass[seg.v_index];
    if (seg.parent != kGround) ws->sliding_force[seg.parent] += ws->sliding_force[i];
  }
  // The segments' accelerations minus gravity, global in sliding_field (whose
  // field is used up), in their own frames in ws->acceleration.
  for (int i = 0; i < n; ++i) {
    const SlidingStructure::Slide& seg = segments[i];
    Vec3 a = seg.parent == kGround ? Vec3(-model.gravity()) : ws->sliding_field[seg.parent];
    if (seg.drive == SegmentDrive::kDof) a += sliding.axis[i] * vdot[seg.v_index];
    if (seg.drive == SegmentDrive::kTime) a += sliding.axis[i] * kin.prescribed[i].acceleration;
    ws->sliding_field[i] = a;
    ws->acceleration[i] << Vec3::Zero(), kin.pose[i].R.transpose() * a;
  }
}

}  // namespace

void ForwardDynamics(const Model& model, const Kinematics& kin, std::span<const double> tau,
                     std::span<const Vec6> external, std::span<double> vdot, DynamicsWorkspace* ws) {
  if (model.sliding())
    SlidingDynamics(model, kin, tau, external, vdot, ws);
  else
    ArticulatedBodyDynamics(model, kin, tau, external, vdot, ws);
}

void ArticulatedBodyDynamics(const Model& model, const Kinematics& kin, std::span<const double> tau,
                             std::span<const Vec6> external, std::span<double> vdot, DynamicsWorkspace* ws) {
  const auto& segments = model.segments();
  const int n = static_cast<int>(segments.size());
  for (int i = 0; i < n; ++i) {
    const Vec6& v = kin.velocity[i];
    ws->articulated_inertia[i] = segments[i].inertia;
    ws->articulated_bias[i] = CrossForce(v, segments[i].inertia * v) - external[i];
  }
  for (int i = n - 1; i >= 0; --i) {
    const Segment& seg = segments[i];
    const Mat6& Ia = ws->articulated_inertia[i];
    const Vec6& pa = ws->articulated_bias[i];
    const Vec6& c = kin.bias[i];
    // What the segment passes to its parent; nothing is passed to the ground,
    // so a root segment skips forming it.
    const bool passes = seg.parent != kGround;
    Mat6 Ia_pass;
    Vec6 pa_pass;
    if (seg.motion == SegmentMotion::kFree) {
      ws->U6[i] = Ia;
      ws->D6[i].compute(Ia);
      if (ws->D6[i].info() != Eigen::Success || !(ws->D6[i].vectorD().minCoeff() > 0.0)) ThrowSingular(model, kin, i);
      for (int k = 0; k < 6; ++k) ws->u6[i](k) = tau[seg.v_index + k] - pa(k);
      if (!passes) continue;
      Ia_pass.setZero();
      pa_pass = pa + ws->u6[i];  // = the joint force itself: a free joint passes nothing else
    } else if (seg.drive == SegmentDrive::kDof) {
      const Vec6& S = kin.axis[i];
      ws->U[i] = Ia * S;
      ws->D[i] = S.dot(ws->U[i]);
      const double scale = Ia.diagonal().cwiseAbs().maxCoeff();
      if (!(ws->D[i] > 1e-14 * scale) || !(ws->D[i] > 0.0)) ThrowSingular(model, kin, i);
      ws->u[i] = tau[seg.v_index] - S.dot(pa);
      if (!passes) continue;
      Ia_pass = Ia - ws->U[i] * ws->U[i].transpose() / ws->D[i];
      pa_pass = pa + Ia_pass * c + ws->U[i] * (ws->u[i] / ws->D[i]);
    } else {  // prescribed: the joint passes everything on
      if (!passes) continue;
      Ia_pass = Ia;
      pa_pass = pa + Ia * c;
    }
    ws->articulated_inertia[seg.parent] += TransformInertiaToParent(kin.X[i], Ia_pass);
    ws->articulated_bias[seg.parent] += kin.X[i].ForceToParent(pa_pass);
  }
  for (int i = 0; i < n; ++i) {
    const Segment& seg = segments[i];
    Vec6 a = ParentAcceleration(model, kin, *ws, i) + kin.bias[i];
    if (seg.motion == SegmentMotion::kFree) {
      const Vec6 qdd = ws->D6[i].solve(ws->u6[i] - ws->U6[i].transpose() * a);
      for (int k = 0; k < 6; ++k) vdot[seg.v_index + k] = qdd(k);
      a += qdd;
    } else if (seg.drive == SegmentDrive::kDof) {
      const double qdd = (ws->u[i] - ws->U[i].dot(a)) / ws->D[i];
      vdot[seg.v_index] = qdd;
      a += kin.axis[i] * qdd;
    }
    ws->acceleration[i] = a;
  }
}

void InverseDynamics(const Model& model, const Kinematics& kin, std::span<const double> vdot,
                     std::span<const Vec6> external, std::span<double> tau, DynamicsWorkspace* ws) {
  const auto& segments = model.segments();
  const int n = static_cast<int>(segments.size());
  for (int i = 0; i < n; ++i) {
    const Segment& seg = segments[i];
    Vec6 a = ParentAcceleration(model, kin, *ws, i) + kin.bias[i];
    if (seg.motion == SegmentMotion::kFree) {
      for (int k = 0; k < 6; ++k) a(k) += vdot[seg.v_index + k];
    } else if (seg.drive == SegmentDrive::kDof) {
      a += kin.axis[i] * vdot[seg.v_index];
    }
    ws->acceleration[i] = a;
    const Vec6& v = kin.velocity[i];
    ws->force[i] = seg.inertia * a + CrossForce(v, seg.inertia * v) - external[i];
  }
  for (int i = n - 1; i >= 0; --i) {
    const Segment& seg = segments[i];
    if (seg.motion == SegmentMotion::kFree) {
      for (int k = 0; k < 6; ++k) tau[seg.v_index + k] = ws->force[i](k);
    } else if (seg.drive == SegmentDrive::kDof) {
      tau[seg.v_index] = kin.axis[i].dot(ws->force[i]);
    }
    if (seg.parent != kGround) ws->force[seg.parent] += kin.X[i].ForceToParent(ws->force[i]);
  }
}

namespace {

// ws->composite[i]: the inertia of segment i and everything it carries, in its frame.
void CompositeInertias(const Model& model, const Kinematics& kin, DynamicsWorkspace* ws) {
  const auto& segments = model.segments();
  const int n = static_cast<int>(segments.size());
  for (int i = 0; i < n; ++i) ws->composite[i] = segments[i].inertia;
  for (int i = n - 1; i >= 0; --i)
    if (segments[i].parent != kGround)
      ws->composite[segments[i].parent] += TransformInertiaToParent(kin.X[i], ws->composite[i]);
}

}  // namespace

void MassMatrixDiagonal(const Model& model, const Kinematics& kin, Eigen::VectorXd* diagonal, DynamicsWorkspace* ws) {
  CompositeInertias(model, kin, ws);
  diagonal->setZero(model.nv());
  const auto& segments = model.segments();
  for (int i = 0; i < static_cast<int>(segments.size()); ++i) {
    const Segment& seg = segments[i];
    if (seg.motion == SegmentMotion::kFree) {  // S = identity: the composite's own diagonal
      diagonal->segment(seg.v_index, 6) = ws->composite[i].diagonal();
    } else if (seg.drive == SegmentDrive::kDof) {
      const Vec6& S = kin.axis[i];
      (*diagonal)(seg.v_index) = S.dot(ws->composite[i] * S);
    }
  }
}

void MassMatrix(const Model& model, const Kinematics& kin, Eigen::MatrixXd* M, DynamicsWorkspace* ws) {
  const auto& segments = model.segments();
  const int n = static_cast<int>(segments.size());
  M->setZero(model.nv(), model.nv());
  CompositeInertias(model, kin, ws);
  using Columns = Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, 6>;
  auto motion_axes = [&](int i) {
    const Segment& seg = segments[i];
    if (seg.motion == SegmentMotion::kFree) return Columns(Mat6::Identity());
    if (seg.drive == SegmentDrive::kDof) return Columns(kin.axis[i]);
    return Columns(6, 0);
  };
  for (int i = 0; i < n; ++i) {
    const Columns Si = motion_axes(i);
    if (Si.cols() == 0) continue;
    const int vi = segments[i].v_index;
    Columns F = ws->composite[i] * Si;
    M->block(vi, vi, Si.cols(), Si.cols()) = Si.transpose() * F;
    for (int j = i; segments[j].parent != kGround;) {
      for (int k = 0; k < F.cols(); ++k) F.col(k) = kin.X[j].ForceToParent(F.col(k));
      j = segments[j].parent;
      const Columns Sj = motion_axes(j);
      if (Sj.cols() == 0) continue;
      const int vj = segments[j].v_index;
      M->block(vi, vj, Si.cols(), Sj.cols()) = F.transpose() * Sj;
      M->block(vj, vi, Sj.cols(), Si.cols()) = M->block(vi, vj, Si.cols(), Sj.cols()).transpose();
    }
  }
}

Vec6 TrueAcceleration(const Model& model, const Kinematics& kin, const DynamicsWorkspace& ws, int segment) {
  // a_true = a + X_global->segment [0; g]
  const Pose& pose = kin.pose[segment];
  Vec6 g;
  g << Vec3::Zero(), pose.R.transpose() * model.gravity();
  // The spatial gravity field [0; g] is uniform: its components about any
  // origin are the same, only rotated.
  return ws.acceleration[segment] + g;
}

Vec3 AngularAcceleration(const Model& model, const Kinematics& kin, const DynamicsWorkspace& ws, int body) {
  const int s = model.bodies()[body].segment;
  if (s == kGround) return Vec3::Zero();
  return kin.pose[s].R * TrueAcceleration(model, kin, ws, s).head<3>();
}

Vec3 PointAcceleration(const Model& model, const Kinematics& kin, const DynamicsWorkspace& ws, int body,
                       const Vec3& local) {
  const Body& b = model.bodies()[body];
  if (b.segment == kGround) return Vec3::Zero();
  const Vec6 a = TrueAcceleration(model, kin, ws, b.segment);
  const Vec6& v = kin.velocity[b.segment];
  const Vec3 r = b.in_segment * local;  // in the segment frame
  const Vec3 w = v.head<3>();
  const Vec3 vel = v.tail<3>() + w.cross(r);
  const Vec3 acc = a.tail<3>() + a.head<3>().cross(r) + w.cross(vel);
  return kin.pose[b.segment].R * acc;
}

}  // namespace mechflow::mech
