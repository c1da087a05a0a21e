#pragma once
// Constraints: the cut joints that close loops, as weld constraints.
//
// A cut joint's own moving transformations hang from body 1 as massless
// "ghost" segments (mech/model.h); its constraint frame G (end of that chain)
// must coincide with the attachment frame B on body 2. Per cut joint six
// equations, in G's axes: rotation error (3) then position error (3). Rows are
// the relative motion of B with respect to G:
//   J v = [R_G^T (w_B - w_G); R_G^T (v_B(x_B) - v_G(x_B))],
// so a multiplier is the wrench [moment about x_B; force] that body 2
// receives, in G's axes. Equations that a loop satisfies identically (a
// planar loop's out-of-plane rows, Convel1's redundant ones) make J rank
// deficient; the solves (mech/constraint_solve.h) accept that redundancy.
//
// A constant-velocity joint (ELEMENTS.md 2.5) gives four rows: the centres
// coincide (p2 - p1, global axes) and the zero-twist condition
// c = R[1][0] - R[0][1] with R = J1^T J2, J_k = A_k [b_k, a_k x b_k, a_k].

#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mech/kinematics.h"

namespace mechflow::mech {

class Constraints {
 public:
  Constraints(const Model& model, std::span<const double> q0);

  int size() const { return size_; }
  int row(int k) const { return cuts_[k].row; }
  int rows(int k) const { return cuts_[k].rows; }
  bool empty() const { return cut_joints_.empty(); }
  const std::vector<int>& cut_joints() const { return cut_joints_; }

  // Position residual phi (size()).
  void Residual(const Model& model, const Kinematics& kin, Eigen::VectorXd* phi) const;
  // J (size() x nv) and the velocity residual's time part: psi_t = J v +
  // psi_t is the relative velocity (prescribed motions included).
  void Jacobian(const Model& model, const Kinematics& kin, Eigen::MatrixXd* J) const;
  // Relative velocity of B w.r.t. G for the current kinematics (= J v + psi_t).
  void VelocityResidual(const Model& model, const Kinematics& kin, Eigen::VectorXd* psi) const;
  // Relative acceleration when v' = 0 (velocity products and prescribed
  // accelerations): J v' + bias = 0 holds on the constraint manifold.
  void AccelerationBias(const Model& model, const Kinematics& kin, std::vector<Vec6>* scratch,
                        Eigen::VectorXd* bias) const;
  // Weld cuts: global pose of the constraint frame G and of B for cut k.
  Pose FrameG(const Model& model, const Kinematics& kin, int k) const;
  Pose FrameB(const Model& model, const Kinematics& kin, int k) const;

  // The loads that multipliers `lambda` of cut k apply: +force at point_b on
  // segment_b with +torque; -force at point_a on segment_a with -torque.
  // Global components; torques about the respective points.
  struct Load {
    int segment_b = kGround, segment_a = kGround;
    Vec3 point_b = Vec3::Zero(), point_a = Vec3::Zero();
    Vec3 force = Vec3::Zero(), torque = Vec3::Zero();
  };
  Load LoadOf(const Model& model, const Kinematics& kin, const Eigen::VectorXd& lambda, int k) const;

 private:
  struct Cut {
    int joint = -1;
    bool convel = false;
    int row = 0, rows = 6;
    Mat3 Q1 = Mat3::Identity(), Q2 = Mat3::Identity();  // convel frames, body axes
  };
  // Convel: the twist-row vector g (global) with c' = g . (w2 - w1).
  Vec3 TwistGradient(const Model& model, const Kinematics& kin, const Cut& cut) const;
  double Twist(const Model& model, const Kinematics& kin, const Cut& cut) const;

  std::vector<Cut> cuts_;
  std::vector<int> cut_joints_;
  int size_ = 0;
};

}  // namespace mechflow::mech
