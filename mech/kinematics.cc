#include "mech/kinematics.h"

#include "mech/sliding_structure.h"

namespace mechflow::mech {
namespace {

Eigen::Quaterniond QuaternionAt(std::span<const double> q, int i) {
  return Eigen::Quaterniond(q[i + 3], q[i + 4], q[i + 5], q[i + 6]).normalized();
}

}  // namespace

Kinematics::Kinematics(const Model& model) {
  const std::size_t ns = model.segments().size(), nb = model.bodies().size();
  X.resize(ns);
  pose.resize(ns);
  axis.assign(ns, Vec6::Zero());
  velocity.assign(ns, Vec6::Zero());
  bias.assign(ns, Vec6::Zero());
  prescribed.resize(ns);
  drives.resize(model.drive_signals().size());
  body_pose.resize(nb);
  body_omega.assign(nb, Vec3::Zero());
  body_velocity.assign(nb, Vec3::Zero());
  const SlidingStructure* sliding = model.sliding();
  if (!sliding) return;
  // What never changes in a sliding model: rotations, motion axes; angular
  // velocities and accelerations stay zero.
  for (std::size_t i = 0; i < ns; ++i) {
    const Segment& seg = model.segments()[i];
    X[i].E = seg.placement.R.transpose();
    pose[i].R = sliding->rotation[i];
    if (seg.motion == SegmentMotion::kRevolute)  // a fixed joint's segment
      axis[i] << seg.axis, Vec3::Zero();
    else
      axis[i] << Vec3::Zero(), seg.axis;
  }
  for (std::size_t b = 0; b < nb; ++b) {
    const Body& body = model.bodies()[b];
    body_pose[b].R = body.segment == kGround ? body.in_segment.R : sliding->rotation[body.segment] * body.in_segment.R;
  }
}

namespace {

// s(t) and its rates of segment i's motion (a Segment or a sliding model's
// packed record of one): a coordinate's, or the time-driven value, which is
// kept in kin->prescribed. Fixed segments stay at zero.
template <class SegmentRecord>
Jet MotionOf(const SegmentRecord& seg, std::size_t i, double t, std::span<const double> q,
             std::span<const double> v, Kinematics* kin) {
  if (seg.drive == SegmentDrive::kTime) {
    kin->prescribed[i] = seg.signal >= 0 ? kin->drives[seg.signal] : seg.function->Evaluate(t);
    return kin->prescribed[i];
  }
  if (seg.drive == SegmentDrive::kDof) return {q[seg.q_index], v[seg.v_index], 0.0};
  return {};
}

// UpdateKinematicsOfTree for a sliding model: the constructor set what the
// rotations fix; only translations and their rates change.
void UpdateSlidingKinematics(const Model& model, double t, std::span<const double> q, std::span<const double> v,
                             Kinematics* kin) {
  kin->time = t;
  ++kin->stamp;
  const SlidingStructure& sliding = *model.sliding();
  for (std::size_t i = 0; i < sliding.slides.size(); ++i) {
    const SlidingStructure::Slide& seg = sliding.slides[i];
    const Jet s = MotionOf(seg, i, t, q, v, kin);
    const Vec3 local = seg.offset + seg.parent_axis * s.value;
    kin->X[i].r = local;
    auto velocity = kin->velocity[i].tail<3>();
    if (seg.parent == kGround) {
      kin->pose[i].p = local;
      velocity = seg.axis * s.rate;
    } else {
      kin->pose[i].p = kin->pose[seg.parent].R * local + kin->pose[seg.parent].p;
      velocity = kin->X[i].E * kin->velocity[seg.parent].tail<3>() + seg.axis * s.rate;
    }
    kin->bias[i].tail<3>() = seg.axis * s.acceleration;
  }
  for (std::size_t b = 0; b < sliding.riders.size(); ++b) {
    const SlidingStructure::Rider& body = sliding.riders[b];
    if (body.segment == kGround) {
      kin->body_pose[b].p = body.offset;
      continue;
    }
    const Pose& sp = kin->pose[body.segment];
    kin->body_pose[b].p = body.turned + sp.p;  // sp.R is sliding.rotation[body.segment]
    kin->body_velocity[b] = sp.R * kin->velocity[body.segment].tail<3>();
  }
}

}  // namespace

void UpdateKinematics(const Model& model, double t, std::span<const double> q, std::span<const double> v,
                      Kinematics* kin) {
  if (model.sliding())
    UpdateSlidingKinematics(model, t, q, v, kin);
  else
    UpdateKinematicsOfTree(model, t, q, v, kin);
}

void UpdateKinematicsOfTree(const Model& model, double t, std::span<const double> q, std::span<const double> v,
                            Kinematics* kin) {
  kin->time = t;
  ++kin->stamp;
  const auto& segments = model.segments();
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const Segment& seg = segments[i];
    Pose local;  // the segment in its parent: placement * joint motion
    Vec6 vJ = Vec6::Zero();
    Vec6 aJ = Vec6::Zero();  // prescribed joint acceleration
    if (seg.motion == SegmentMotion::kFree) {
      local = seg.placement * Pose{QuaternionAt(q, seg.q_index).toRotationMatrix(),
                                   Vec3(q[seg.q_index], q[seg.q_index + 1], q[seg.q_index + 2])};
      for (int k = 0; k < 6; ++k) vJ(k) = v[seg.v_index + k];
    } else {
      const Jet s = MotionOf(seg, i, t, q, v, kin);
      Vec6& S = kin->axis[i];
      if (seg.motion == SegmentMotion::kRevolute) {
        local = {seg.placement.R * AxisRotation(seg.axis, s.value), seg.placement.p};
        S << seg.axis, Vec3::Zero();
      } else {  // a translation leaves the placement's rotation as it is
        local = {seg.placement.R, seg.placement.p + seg.placement.R * (seg.axis * s.value)};
        S << Vec3::Zero(), seg.axis;
      }
      vJ = S * s.rate;
      aJ = S * s.acceleration;
    }
    kin->X[i] = SpatialTransform::FromPose(local);
    if (seg.parent == kGround) {
      kin->pose[i] = local;
      kin->velocity[i] = vJ;
      kin->bias[i] = aJ;
    } else {
      kin->pose[i] = kin->pose[seg.parent] * local;
      const Vec6 v_parent = kin->X[i].Motion(kin->velocity[seg.parent]);
      kin->velocity[i] = v_parent + vJ;
      kin->bias[i] = CrossMotion(kin->velocity[i], vJ) + aJ;
    }
  }
  for (std::size_t b = 0; b < model.bodies().size(); ++b) {
    const Body& body = model.bodies()[b];
    if (body.segment == kGround) {
      kin->body_pose[b] = body.in_segment;
      kin->body_omega[b].setZero();
      kin->body_velocity[b].setZero();
      continue;
    }
    const Pose& sp = kin->pose[body.segment];
    const Vec6& sv = kin->velocity[body.segment];
    kin->body_pose[b] = sp * body.in_segment;
    kin->body_omega[b] = sp.R * sv.head<3>();
    kin->body_velocity[b] = sp.R * (sv.tail<3>() + sv.head<3>().cross(body.in_segment.p));
  }
}

void CoordinateRates(const Model& model, std::span<const double> q, std::span<const double> v,
                     std::span<double> qdot) {
  if (!model.has_quaternions()) {
    for (int i = 0; i < model.nv(); ++i) qdot[i] = v[i];
    return;
  }
  for (const Dof& dof : model.dofs()) qdot[dof.q_index] = v[dof.v_index];
  for (const Segment& seg : model.segments()) {
    if (seg.motion != SegmentMotion::kFree) continue;
    const int iq = seg.q_index, iv = seg.v_index;
    const Eigen::Quaterniond quat(q[iq + 3], q[iq + 4], q[iq + 5], q[iq + 6]);
    const Vec3 omega(v[iv], v[iv + 1], v[iv + 2]);
    const Vec3 lin(v[iv + 3], v[iv + 4], v[iv + 5]);
    const Vec3 pdot = quat.normalized().toRotationMatrix() * lin;
    // q' = 1/2 q (x) (0, omega)
    const Eigen::Quaterniond rate = quat * Eigen::Quaterniond(0.0, omega.x(), omega.y(), omega.z());
    qdot[iq] = pdot.x();
    qdot[iq + 1] = pdot.y();
    qdot[iq + 2] = pdot.z();
    qdot[iq + 3] = 0.5 * rate.w();
    qdot[iq + 4] = 0.5 * rate.x();
    qdot[iq + 5] = 0.5 * rate.y();
    qdot[iq + 6] = 0.5 * rate.z();
  }
}

// 1/2 m |v_c|^2 + 1/2 w . (R I R^T) w of body b.
double KineticEnergy(const Model& model, const Kinematics& kin, int b) {
  const Body& body = model.bodies()[b];
  const Vec3 v = PointVelocity(kin, b, body.com);
  const Vec3& w = kin.body_omega[b];
  const Mat3& R = kin.body_pose[b].R;
  return 0.5 * body.mass * v.squaredNorm() + 0.5 * w.dot(R * body.inertia * R.transpose() * w);
}

// -m g . r_c of body b: zero at the global origin.
double PotentialEnergy(const Model& model, const Kinematics& kin, int b) {
  const Body& body = model.bodies()[b];
  return -body.mass * model.gravity().dot(PointPosition(kin, b, body.com));
}

}  // namespace mechflow::mech
