#pragma once
// Kinematics: positions and velocities of every segment and body for one
// (t, q, v), computed root to leaves, plus the queries force elements and
// sensors need (points, frames).
//
// Storage is allocated once per model (constructor); Update() allocates
// nothing. Spatial quantities of a segment are in its own frame, about its
// origin; body quantities are global.

#include <cstdint>
#include <span>
#include <vector>

#include "mech/model.h"

namespace mechflow::mech {

struct Kinematics {
  explicit Kinematics(const Model& model);

  double time = 0.0;
  // Counts the updates: what was computed from these kinematics (element
  // sensors) is known to be current while it is unchanged.
  std::uint64_t stamp = 0;
  // per segment
  std::vector<SpatialTransform> X;  // parent -> segment
  std::vector<Pose> pose;           // segment frame in global
  std::vector<Vec6> axis;           // motion axis S (revolute/prismatic), segment frame
  std::vector<Vec6> velocity;       // spatial velocity, segment frame
  std::vector<Vec6> bias;           // acceleration when the DOF accelerations are zero, minus the parent's
  std::vector<Jet> prescribed;      // s(t) of time-driven segments
  // Values of Model::drive_signals, set by the owner before each update.
  std::vector<Jet> drives;
  // per body (global)
  std::vector<Pose> body_pose;
  std::vector<Vec3> body_omega;
  std::vector<Vec3> body_velocity;  // velocity of the body frame's origin
};

// Fills `kin` for time t and coordinates q (nq), v (nv): for a sliding
// model (Model::sliding) its translations only, else UpdateKinematicsOfTree.
void UpdateKinematics(const Model& model, double t, std::span<const double> q, std::span<const double> v,
                      Kinematics* kin);
// The same for any tree: every segment placed and moved from its parent's
// frame (the sliding case's reference in the tests).
void UpdateKinematicsOfTree(const Model& model, double t, std::span<const double> q, std::span<const double> v,
                            Kinematics* kin);

// Global position and velocity of a point fixed on `body`, given in the body frame.
inline Vec3 PointPosition(const Kinematics& kin, int body, const Vec3& local) {
  return kin.body_pose[body] * local;
}
inline Vec3 PointVelocity(const Kinematics& kin, int body, const Vec3& local) {
  return kin.body_velocity[body] + kin.body_omega[body].cross(kin.body_pose[body].R * local);
}
// Velocity of the material point of `body` that is at the global position x.
inline Vec3 MaterialVelocityAt(const Kinematics& kin, int body, const Vec3& x) {
  return kin.body_velocity[body] + kin.body_omega[body].cross(x - kin.body_pose[body].p);
}

// q' from v: equal for scalar coordinates; quaternion joints map (omega, v)
// in body axes to (p', quaternion').
void CoordinateRates(const Model& model, std::span<const double> q, std::span<const double> v,
                     std::span<double> qdot);

// Kinetic energy 1/2 m |v_c|^2 + 1/2 w . I w of body b [J].
double KineticEnergy(const Model& model, const Kinematics& kin, int b);
// Gravitational potential energy -m g . r_c of body b, zero at the global origin [J].
double PotentialEnergy(const Model& model, const Kinematics& kin, int b);

}  // namespace mechflow::mech
