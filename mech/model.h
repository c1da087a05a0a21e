#pragma once
// Model: the immutable, compiled form of a mechanism (bodies, joints, the
// spanning tree, loop-closing joints) and the layout of its coordinates.
//
// A joint is a chain of elementary transformations (ELEMENTS.md 2.1-2.2) from
// an attachment frame on body 1 to an attachment frame on body 2. Compilation
// folds the constant transformations (tc, rc, locked DOFs) into fixed
// placements and turns every remaining moving transformation (tv, rv: a degree
// of freedom; tt, rt: prescribed in time) into one *segment*: a frame that
// moves along or about a single axis relative to its parent segment. The
// quaternion joint becomes one free segment. Bodies ride on segments: a body's
// inertia is carried by the segment its joint ends on (intermediate segments
// are massless). The recursive algorithms (mech/dynamics.h) then see a tree of
// single-axis and free segments, whatever joints the user wrote.
//
// Tree: a joint is a tree joint when its body 1 is already connected to Base0
// (through tree joints, in file order) and its body 2 is not; a joint whose
// two bodies are both connected already closes a loop and becomes a *cut
// joint*: its own moving transformations become massless segments hanging from
// body 1 (a "ghost" chain), and a weld constraint ties the ghost's end frame to
// body 2's attachment frame (mech/constraints.h).
//
// Coordinates: q (positions, nq) and v (velocities, nv); nq = nv except for
// quaternion joints (7 positions, 6 velocities: [omega; v] in body 2 axes).

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "mech/spatial.h"
#include "mech/time_function.h"

namespace mechflow::mech {

inline constexpr int kGround = -1;  // parent of root segments; Base0 is body 0

enum class SegmentMotion { kRevolute, kPrismatic, kFree };
// kNone: a fixed joint's segment, kept so the joint's reaction is computed.
enum class SegmentDrive { kDof, kTime, kNone };

struct Segment {
  int parent = kGround;      // segment index
  Pose placement;            // joint frame in the parent segment's frame (constant)
  SegmentMotion motion = SegmentMotion::kRevolute;
  SegmentDrive drive = SegmentDrive::kDof;
  Vec3 axis = Vec3::UnitZ();  // unit, in the joint frame (revolute/prismatic)
  int q_index = -1;           // first position coordinate (kDof)
  int v_index = -1;           // first velocity coordinate (kDof)
  std::shared_ptr<const TimeFunction> function;  // kTime, unless driven by a signal
  int signal = -1;  // kTime driven by a signal: index into Model::drive_signals and Kinematics::drives
  Mat6 inertia = Mat6::Zero();  // spatial inertia of the bodies it carries, in its frame
  int joint = -1;               // the joint this segment belongs to
  bool ghost = false;           // part of a cut joint's chain (massless)
};

struct NamedPoint {
  std::string name;
  Vec3 position;  // body frame
};

struct Body {
  std::string name;
  double mass = 0.0;
  Vec3 com = Vec3::Zero();      // body frame
  Mat3 inertia = Mat3::Zero();  // about the centre of mass, body axes
  std::vector<NamedPoint> points;
  int segment = kGround;        // the segment the body rides on (kGround: Base0 or welded to it)
  Pose in_segment;              // body frame in that segment's frame
  std::string origin;           // "file:line" for messages
};

// One coordinate of the model, as a user names it ("jBox", "jCube.z").
struct Dof {
  std::string name;
  int joint = -1;
  int q_index = -1;
  int v_index = -1;
  bool rotational = false;
};

struct Joint {
  std::string name;
  int body1 = 0, body2 = 0;
  bool is_cut = false;
  int first_segment = kGround;  // tree joints: the segment whose transmitted force is the reaction
  int last_segment = kGround;   // body 2 side (tree) or ghost end (cut)
  Pose end_offset;             // from last_segment's frame to body 2's frame (tree) or to the
                               // constraint frame (cut: that frame must coincide with body 2's
                               // attachment frame)
  Pose body2_attachment;       // cut joints: attachment frame in body 2's frame
  std::vector<int> dofs;       // indices into Model::dofs
  // Constant-velocity joint (ELEMENTS.md 2.5): always a constraint. Centres
  // are frame1.p / frame2.p of the spec; axes unit; references zero = auto.
  bool convel = false;
  Vec3 cv_point1 = Vec3::Zero(), cv_point2 = Vec3::Zero();
  Vec3 cv_axis1 = Vec3::UnitZ(), cv_axis2 = Vec3::UnitZ();
  Vec3 cv_reference1 = Vec3::Zero(), cv_reference2 = Vec3::Zero();
  std::string origin;
};

struct SlidingStructure;

class Model {
 public:
  const std::vector<Body>& bodies() const { return bodies_; }
  const std::vector<Joint>& joints() const { return joints_; }
  const std::vector<Segment>& segments() const { return segments_; }
  const std::vector<Dof>& dofs() const { return dofs_; }
  // Names of the signals that drive segments (tt/rt given by a signal rather
  // than a function of time); Kinematics::drives holds their values.
  const std::vector<std::string>& drive_signals() const { return drive_signals_; }
  const Vec3& gravity() const { return gravity_; }
  int nq() const { return nq_; }
  int nv() const { return nv_; }
  int num_bodies() const { return static_cast<int>(bodies_.size()); }
  int num_cut_joints() const { return num_cut_joints_; }
  bool has_quaternions() const { return has_quaternions_; }
  // The sliding structure (mech/sliding_structure.h), or null when some
  // frame turns; then not_sliding() says which joint and why.
  const SlidingStructure* sliding() const { return sliding_.get(); }
  const std::string& not_sliding() const { return not_sliding_; }

  // Index or -1; names are exact.
  int FindBody(const std::string& name) const;
  int FindJoint(const std::string& name) const;
  int FindDof(const std::string& name) const;

  // Initial coordinates given in the description (before loop assembly).
  const std::vector<double>& initial_q() const { return initial_q_; }
  const std::vector<double>& initial_v() const { return initial_v_; }

 private:
  friend class ModelBuilder;
  std::vector<Body> bodies_;
  std::vector<Joint> joints_;
  std::vector<Segment> segments_;
  std::vector<Dof> dofs_;
  std::vector<std::string> drive_signals_;
  // name -> index, for the Find functions (a linear search per name made
  // building a long chain quadratic)
  std::map<std::string, int, std::less<>> body_index_, joint_index_, dof_index_;
  Vec3 gravity_{0.0, 0.0, -9.81};
  int nq_ = 0, nv_ = 0;
  int num_cut_joints_ = 0;
  bool has_quaternions_ = false;
  std::vector<double> initial_q_, initial_v_;
  std::shared_ptr<const SlidingStructure> sliding_;
  std::string not_sliding_;
};

}  // namespace mechflow::mech
