#pragma once
// Recursive dynamics over the segment tree (Featherstone, "Rigid Body Dynamics
// Algorithms", 2008): the articulated-body algorithm for forward dynamics,
// recursive Newton-Euler for inverse dynamics and reaction forces, and the
// composite-rigid-body algorithm for the joint-space mass matrix. All three
// work on the same Kinematics, so tests can check one against the others.
//
// Gravity enters as an upward acceleration of the ground (a0 = -g), so the
// accelerations the algorithms work with are "true acceleration minus
// gravity"; TrueAcceleration() converts.
//
// External loads are spatial forces per segment, in the segment's frame,
// about its origin, acting ON the segment. Time-driven segments move as
// prescribed; they have no coordinate and their driving force is a reaction.

#include <span>
#include <vector>

#include <Eigen/Core>

#include "mech/kinematics.h"

namespace mechflow::mech {

class DynamicsWorkspace {
 public:
  explicit DynamicsWorkspace(const Model& model);

  std::vector<Mat6> articulated_inertia;
  std::vector<Vec6> articulated_bias;
  std::vector<Vec6> U;
  std::vector<double> D, u;
  std::vector<Mat6> U6;                 // free segments
  std::vector<Eigen::LDLT<Mat6>> D6;   // free segments
  std::vector<Vec6> u6;
  std::vector<Vec6> acceleration;  // per segment, segment frame (minus gravity)
  std::vector<Vec6> force;         // RNEA: force transmitted from the parent across the joint
  std::vector<Mat6> composite;     // CRBA
  // Sliding models (mech/sliding_structure.h), global components: the
  // acceleration gravity and the time-driven segments leave to the bodies a
  // segment carries, and the force on everything it carries.
  std::vector<Vec3> sliding_field, sliding_force;
};

// v' (nv) from generalized forces tau (nv) and external segment loads; fills
// ws->acceleration. A sliding model's coordinates accelerate on their own
// (mech/sliding_structure.h); any other tree takes ArticulatedBodyDynamics.
void ForwardDynamics(const Model& model, const Kinematics& kin, std::span<const double> tau,
                     std::span<const Vec6> external, std::span<double> vdot, DynamicsWorkspace* ws);
// Articulated-body algorithm, for any tree. Throws SimulationError when a
// joint axis carries no inertia (singular mass matrix).
void ArticulatedBodyDynamics(const Model& model, const Kinematics& kin, std::span<const double> tau,
                             std::span<const Vec6> external, std::span<double> vdot, DynamicsWorkspace* ws);

// Recursive Newton-Euler: the generalized forces tau (nv) that produce v'
// under the external loads. Fills ws->acceleration and ws->force.
void InverseDynamics(const Model& model, const Kinematics& kin, std::span<const double> vdot,
                     std::span<const Vec6> external, std::span<double> tau, DynamicsWorkspace* ws);

// Composite-rigid-body algorithm: the symmetric nv x nv mass matrix.
void MassMatrix(const Model& model, const Kinematics& kin, Eigen::MatrixXd* M, DynamicsWorkspace* ws);
// Its diagonal alone (nv), M_ii = S_i^T Ic_i S_i with Ic_i the composite
// inertia of what coordinate i carries: linear in the segments, where M
// itself is quadratic (dense for a serial chain).
void MassMatrixDiagonal(const Model& model, const Kinematics& kin, Eigen::VectorXd* diagonal, DynamicsWorkspace* ws);

// The segment's true spatial acceleration from the algorithms' one.
Vec6 TrueAcceleration(const Model& model, const Kinematics& kin, const DynamicsWorkspace& ws, int segment);

// Classical (global) acceleration of a point fixed on `body`, given in the body
// frame, after ForwardDynamics or InverseDynamics.
Vec3 PointAcceleration(const Model& model, const Kinematics& kin, const DynamicsWorkspace& ws, int body,
                       const Vec3& local);
// Global angular acceleration of `body`.
Vec3 AngularAcceleration(const Model& model, const Kinematics& kin, const DynamicsWorkspace& ws, int body);

}  // namespace mechflow::mech
