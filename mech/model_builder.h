#pragma once
// ModelBuilder: checks a mechanism described as plain values and compiles it
// into an immutable Model (mech/model.h). Single use: Build() once.
//
// Every error is an InputError starting with the item's origin ("file:line")
// and naming the body or joint: non-positive mass, an inertia tensor that is
// not symmetric positive definite or violates the triangle inequality, a zero
// axis, an unknown or repeated name, a body not connected to Base0.

#include <memory>
#include <set>
#include <string>
#include <vector>

#include "mech/model.h"

namespace mechflow::mech {

enum class TransformType { kTc, kTt, kTv, kRc, kRt, kRv };

struct TransformSpec {
  TransformType type = TransformType::kTc;
  Vec3 axis = Vec3::UnitX();  // any length but zero; in the frame the ETs before it produce
  double value = 0.0;         // tc/rc: the constant (tc moves value * unit axis); tv/rv: initial coordinate
  double rate = 0.0;          // tv/rv: the initial velocity
  bool locked = false;        // tv/rv switched off: stays at `value`
  std::shared_ptr<const TimeFunction> function;  // tt/rt
  std::string signal;         // tt/rt driven by this signal instead of `function`
  std::string dof_name;       // tv/rv: optional; default: the joint's name (one DOF) or joint.k
  std::string origin;
};

struct BodySpec {
  std::string name;
  double mass = 0.0;
  Vec3 com = Vec3::Zero();
  Mat3 inertia = Mat3::Zero();  // about the centre of mass, body axes
  std::vector<NamedPoint> points;
  std::string origin;
};

struct QuaternionJointSpec {
  Vec3 position = Vec3::Zero();                                // body 2 origin, joint frame 1 axes
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  Vec3 velocity = Vec3::Zero();                                // joint frame 1 axes
  Vec3 angular_velocity = Vec3::Zero();                        // body 2 axes
};

struct JointSpec {
  std::string name;
  std::string body1, body2;
  Pose frame1;  // attachment frame on body 1, in body 1's frame
  Pose frame2;  // attachment frame on body 2, in body 2's frame
  std::vector<TransformSpec> chain;
  bool quaternion = false;  // the quaternion 6-DOF joint instead of a chain
  QuaternionJointSpec quaternion_initial;
  // The constant-velocity joint instead of a chain: joint centres frame1.p and
  // frame2.p, shaft axes in the body frames, optional zero-phase references
  // (perpendicular to the axes; zero: chosen for zero initial twist).
  bool convel = false;
  Vec3 convel_axis1 = Vec3::UnitZ(), convel_axis2 = Vec3::UnitZ();
  Vec3 convel_reference1 = Vec3::Zero(), convel_reference2 = Vec3::Zero();
  std::string origin;
};

class ModelBuilder {
 public:
  ModelBuilder();  // starts with Base0
  void SetGravity(const Vec3& g) { model_->gravity_ = g; }
  void AddBody(BodySpec body);
  void AddJoint(JointSpec joint);
  std::shared_ptr<const Model> Build();

 private:
  void CompileTreeJoint(const JointSpec& spec, int joint_index);
  void CompileCutJoint(const JointSpec& spec, int joint_index);
  // Appends the moving transformations of `chain` as segments below `parent`
  // (placed by `start`); returns the last segment and the remaining constant
  // offset.
  int AppendChain(const JointSpec& spec, int joint_index, int parent, Pose start, bool ghost, Pose* end);
  int AddDof(const std::string& name, int joint, bool rotational, double q0, double v0);

  std::unique_ptr<Model> model_;
  std::vector<JointSpec> joint_specs_;
  std::set<std::string> joint_names_;
  bool built_ = false;
};

}  // namespace mechflow::mech
