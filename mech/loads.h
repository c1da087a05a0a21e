#pragma once
// Loads: the applied forces of one evaluation, gathered from force elements
// and inputs, in the form the dynamics consumes (a spatial force per segment,
// a generalized force per velocity coordinate). Allocated once; Clear() and
// the Add* calls do not allocate.

#include <span>
#include <vector>

#include "mech/kinematics.h"

namespace mechflow::mech {

class Loads {
 public:
  explicit Loads(const Model& model)
      : model_(&model), segment_(model.segments().size(), Vec6::Zero()), tau_(model.nv(), 0.0) {}

  void Clear() {
    for (Vec6& f : segment_) f.setZero();
    for (double& t : tau_) t = 0.0;
  }
  // A force (global components) acting on `body` at the global point x.
  // Loads on Base0 (or bodies welded to it) are taken by the ground.
  void AddForce(const Kinematics& kin, int body, const Vec3& x, const Vec3& force) {
    const int s = model_->bodies()[body].segment;
    if (s == kGround) return;
    const Pose& pose = kin.pose[s];
    const Vec3 f = pose.R.transpose() * force;
    const Vec3 r = pose.R.transpose() * (x - pose.p);
    segment_[s].head<3>() += r.cross(f);
    segment_[s].tail<3>() += f;
  }
  // A pure moment (global components) on `body`.
  void AddTorque(const Kinematics& kin, int body, const Vec3& torque) {
    const int s = model_->bodies()[body].segment;
    if (s == kGround) return;
    segment_[s].head<3>() += kin.pose[s].R.transpose() * torque;
  }
  // A generalized force on velocity coordinate `v_index` (a joint force).
  void AddGeneralizedForce(int v_index, double value) { tau_[v_index] += value; }

  std::span<const Vec6> segment_loads() const { return segment_; }
  std::span<const double> generalized() const { return tau_; }

 private:
  const Model* model_;
  std::vector<Vec6> segment_;
  std::vector<double> tau_;
};

}  // namespace mechflow::mech
