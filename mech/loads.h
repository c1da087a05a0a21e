#pragma once
// Loads: the applied forces of one evaluation, gathered from force elements
// and inputs, in the form the dynamics consumes (a spatial force per segment,
// a generalized force per velocity coordinate). Allocated once; Clear() and
// the Add* calls do not allocate.
//
// When asked (TrackPower), it also sums the power of every load it takes --
// force . velocity of its point, moment . angular velocity, generalized force
// times rate -- so the mechanism can integrate each element's work on the
// bodies (the energy balance) from the difference before and after it.

#include <span>
#include <vector>

#include "mech/kinematics.h"

namespace mechflow::mech {

class Loads {
 public:
  explicit Loads(const Model& model) : segment_(model.segments().size(), Vec6::Zero()), tau_(model.nv(), 0.0) {
    for (const Body& body : model.bodies()) segment_of_body_.push_back(body.segment);
  }

  void Clear() {
    for (Vec6& f : segment_) f.setZero();
    for (double& t : tau_) t = 0.0;
    power_ = 0.0;
    discard_ = false;  // also after an evaluation for sensors that threw
  }
  // Sums the loads' power from now on (segment velocities from the
  // kinematics the Add* calls get, generalized ones from v). v may be
  // empty: a mechanism whose every joint time drives has no velocity
  // coordinates, but its bodies move and its elements do work.
  void TrackPower(std::span<const double> v) {
    v_ = v;
    track_power_ = true;
  }
  double power() const { return power_; }
  // A force (global components) acting on `body` at the global point x.
  // Loads on Base0 (or bodies welded to it) are taken by the ground.
  void AddForce(const Kinematics& kin, int body, const Vec3& x, const Vec3& force) {
    const int s = segment_of_body_[body];
    if (s == kGround || discard_) return;
    const Pose& pose = kin.pose[s];
    const Vec3 f = pose.R.transpose() * force;
    const Vec3 r = pose.R.transpose() * (x - pose.p);
    segment_[s].head<3>() += r.cross(f);
    segment_[s].tail<3>() += f;
    if (track_power_) {
      const Vec6& velocity = kin.velocity[s];
      power_ += f.dot(velocity.tail<3>() + velocity.head<3>().cross(r));
    }
  }
  // A pure moment (global components) on `body`.
  void AddTorque(const Kinematics& kin, int body, const Vec3& torque) {
    const int s = segment_of_body_[body];
    if (s == kGround || discard_) return;
    const Vec3 moment = kin.pose[s].R.transpose() * torque;
    segment_[s].head<3>() += moment;
    if (track_power_) power_ += moment.dot(kin.velocity[s].head<3>());
  }
  // A generalized force on velocity coordinate `v_index` (a joint force).
  void AddGeneralizedForce(int v_index, double value) {
    if (discard_) return;
    tau_[v_index] += value;
    if (track_power_) power_ += value * v_[v_index];
  }

  // While set (until Clear), the Add* calls take nothing: an evaluation
  // for sensors alone (an output row) needs the elements' values, not
  // their loads. Not with TrackPower (the work sensors need the loads' power).
  void SetDiscard(bool discard) { discard_ = discard; }

  std::span<const Vec6> segment_loads() const { return segment_; }
  std::span<const double> generalized() const { return tau_; }

 private:
  std::vector<int> segment_of_body_;  // the model's bodies are large records; this one stays in the cache
  std::vector<Vec6> segment_;
  std::vector<double> tau_;
  std::span<const double> v_;
  bool track_power_ = false;
  double power_ = 0.0;
  bool discard_ = false;
};

}  // namespace mechflow::mech
