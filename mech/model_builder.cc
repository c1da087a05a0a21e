#include "mech/model_builder.h"

#include <algorithm>
#include <cmath>
#include <queue>
#include <sstream>

#include <Eigen/Eigenvalues>

#include "mech/dynamics.h"
#include "mech/errors.h"
#include "mech/kinematics.h"
#include "mech/sliding_structure.h"

namespace mechflow::mech {
namespace {

std::string Where(const std::string& origin) { return origin.empty() ? std::string() : origin + ": "; }

std::string Num(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

void CheckBody(const BodySpec& b) {
  const std::string where = Where(b.origin) + "body '" + b.name + "': ";
  if (!(b.mass > 0.0) || !std::isfinite(b.mass))
    throw InputError(where + "mass must be a positive number of kg (got " + Num(b.mass) + ")");
  const Mat3& I = b.inertia;
  if (!I.allFinite() || (I - I.transpose()).cwiseAbs().maxCoeff() > 1e-12 * (1.0 + I.cwiseAbs().maxCoeff()))
    throw InputError(where + "inertia tensor must be symmetric (Ixy = Iyx, Ixz = Izx, Iyz = Izy)");
  Eigen::SelfAdjointEigenSolver<Mat3> eig(I);
  const Vec3 p = eig.eigenvalues();  // ascending
  // zero is a point mass (or a thin rod's axis), accepted where no rotation
  // about its centre of mass needs it (CheckRotationsCarryInertia)
  if (!(p(0) >= -1e-12 * p(2)))
    throw InputError(where + "inertia tensor must be positive semi-definite (smallest principal moment " + Num(p(0)) +
                     " kg m^2)");
  // A rigid body's principal moments obey I1 + I2 >= I3 (rounding allowed).
  if (p(0) + p(1) < p(2) * (1.0 - 1e-9))
    throw InputError(where + "principal moments " + Num(p(0)) + ", " + Num(p(1)) + ", " + Num(p(2)) +
                     " violate the triangle inequality I1 + I2 >= I3: no rigid body has them");
  if (!b.com.allFinite()) throw InputError(where + "centre of mass must be finite");
}

// Every degree of freedom must move some mass: with point masses (zero
// inertia) a rotation about an axis through them alone would make the mass
// matrix singular. Checked on the mass matrix at the initial coordinates:
// each coordinate's own entry (ghost coordinates of cut joints are massless
// by design and fixed by their loops). Only the diagonal is formed: M is
// dense for a serial chain (2 GB at 16000 coordinates).
void CheckRotationsCarryInertia(const Model& m) {
  Kinematics kin(m);
  const std::vector<double> v(m.nv(), 0.0);
  UpdateKinematics(m, 0.0, m.initial_q(), v, &kin);
  DynamicsWorkspace dyn(m);
  Eigen::VectorXd diagonal;
  MassMatrixDiagonal(m, kin, &diagonal, &dyn);
  const double scale = diagonal.size() > 0 ? diagonal.cwiseAbs().maxCoeff() : 0.0;
  static const char* const kFreeNames[6] = {"wx", "wy", "wz", "vx", "vy", "vz"};
  for (const Segment& seg : m.segments()) {
    if (seg.drive != SegmentDrive::kDof || seg.ghost) continue;
    const bool free = seg.motion == SegmentMotion::kFree;
    for (int c = 0; c < (free ? 6 : 1); ++c) {
      const int column = seg.v_index + c;
      if (diagonal(column) > 1e-12 * scale) continue;
      const Joint& joint = m.joints()[seg.joint];
      std::string coordinate = joint.name + "." + kFreeNames[c];
      for (const Dof& dof : m.dofs())
        if (!free && dof.v_index == column) coordinate = dof.name;
      throw InputError(Where(joint.origin) + "joint '" + joint.name + "': coordinate '" + coordinate +
                       "' turns body '" + m.bodies()[joint.body2].name +
                       "' (and what it carries) about an axis through their centre of mass, and none of them has "
                       "rotational inertia about it (a point mass, or a thin rod about its own axis): the mass "
                       "matrix is singular. Give the body inertia, or move its centre of mass off that axis");
    }
  }
}

bool IsVariable(TransformType t) { return t == TransformType::kTv || t == TransformType::kRv; }
bool IsTimed(TransformType t) { return t == TransformType::kTt || t == TransformType::kRt; }
bool IsRotation(TransformType t) {
  return t == TransformType::kRc || t == TransformType::kRt || t == TransformType::kRv;
}

}  // namespace

namespace {

int Lookup(const std::map<std::string, int, std::less<>>& index, const std::string& name) {
  const auto it = index.find(name);
  return it == index.end() ? -1 : it->second;
}

}  // namespace

int Model::FindBody(const std::string& name) const { return Lookup(body_index_, name); }
int Model::FindJoint(const std::string& name) const { return Lookup(joint_index_, name); }
int Model::FindDof(const std::string& name) const { return Lookup(dof_index_, name); }

ModelBuilder::ModelBuilder() : model_(new Model) {
  Body base;
  base.name = "Base0";
  model_->body_index_.emplace(base.name, 0);
  model_->bodies_.push_back(base);
}

void ModelBuilder::AddBody(BodySpec spec) {
  if (built_) throw std::logic_error("ModelBuilder used after Build()");
  CheckBody(spec);
  if (model_->FindBody(spec.name) >= 0)
    throw InputError(Where(spec.origin) + "body '" + spec.name + "' is defined twice");
  Body body;
  body.name = spec.name;
  body.mass = spec.mass;
  body.com = spec.com;
  body.inertia = spec.inertia;
  body.points = std::move(spec.points);
  body.origin = spec.origin;
  model_->body_index_.emplace(body.name, model_->num_bodies());
  model_->bodies_.push_back(std::move(body));
}

void ModelBuilder::AddJoint(JointSpec spec) {
  if (built_) throw std::logic_error("ModelBuilder used after Build()");
  const std::string where = Where(spec.origin) + "joint '" + spec.name + "': ";
  if (!joint_names_.insert(spec.name).second)
    throw InputError(Where(spec.origin) + "joint '" + spec.name + "' is defined twice");
  for (const std::string* body : {&spec.body1, &spec.body2})
    if (model_->FindBody(*body) < 0)
      throw InputError(where + "unknown body '" + *body + "' (bodies are defined before the joints that use them)");
  if (spec.body1 == spec.body2) throw InputError(where + "body 1 and body 2 are the same body '" + spec.body1 + "'");
  for (std::size_t k = 0; k < spec.chain.size(); ++k) {
    const TransformSpec& et = spec.chain[k];
    const std::string et_where = Where(et.origin.empty() ? spec.origin : et.origin) + "joint '" + spec.name +
                                 "' transformation " + std::to_string(k + 1) + ": ";
    if (!(et.axis.norm() > 0.0) || !et.axis.allFinite())
      throw InputError(et_where + "axis vector must be non-zero");
    if (IsTimed(et.type) && !et.function == et.signal.empty())
      throw InputError(et_where + "a time function or a driving signal is required (one of the two)");
    if (!std::isfinite(et.value) || !std::isfinite(et.rate)) throw InputError(et_where + "values must be finite");
  }
  joint_specs_.push_back(std::move(spec));
}

int ModelBuilder::AddDof(const std::string& name, int joint, bool rotational, double q0, double v0) {
  Model& m = *model_;
  if (m.FindDof(name) >= 0)
    throw InputError(Where(joint_specs_[joint].origin) + "joint '" + joint_specs_[joint].name +
                     "': coordinate name '" + name + "' is used twice");
  Dof dof{name, joint, m.nq_, m.nv_, rotational};
  m.dof_index_.emplace(name, static_cast<int>(m.dofs_.size()));
  m.dofs_.push_back(dof);
  m.initial_q_.push_back(q0);
  m.initial_v_.push_back(v0);
  ++m.nq_;
  ++m.nv_;
  return static_cast<int>(m.dofs_.size()) - 1;
}

int ModelBuilder::AppendChain(const JointSpec& spec, int joint_index, int parent, Pose pending, bool ghost,
                              Pose* end) {
  Model& m = *model_;
  int num_variable = 0;
  for (const auto& et : spec.chain)
    if (IsVariable(et.type) && !et.locked) ++num_variable;
  int k_variable = 0;
  for (const auto& et : spec.chain) {
    const Vec3 axis = et.axis.normalized();
    const bool moving = IsTimed(et.type) || (IsVariable(et.type) && !et.locked);
    if (!moving) {
      const double s = et.value;
      pending = IsRotation(et.type) ? pending * Pose::Rotation(AxisRotation(axis, s))
                                    : pending * Pose::Translation(axis * s);
      continue;
    }
    Segment seg;
    seg.parent = parent;
    seg.placement = pending;
    seg.motion = IsRotation(et.type) ? SegmentMotion::kRevolute : SegmentMotion::kPrismatic;
    seg.axis = axis;
    seg.joint = joint_index;
    seg.ghost = ghost;
    if (IsTimed(et.type)) {
      seg.drive = SegmentDrive::kTime;
      seg.function = et.function;
      if (!et.signal.empty()) {
        auto& names = m.drive_signals_;
        seg.signal = static_cast<int>(std::find(names.begin(), names.end(), et.signal) - names.begin());
        if (seg.signal == static_cast<int>(names.size())) names.push_back(et.signal);
      }
    } else {
      ++k_variable;
      std::string name = et.dof_name;
      if (name.empty()) name = num_variable == 1 ? spec.name : spec.name + "." + std::to_string(k_variable);
      const int dof = AddDof(name, joint_index, IsRotation(et.type), et.value, et.rate);
      seg.drive = SegmentDrive::kDof;
      seg.q_index = m.dofs_[dof].q_index;
      seg.v_index = m.dofs_[dof].v_index;
      m.joints_[joint_index].dofs.push_back(dof);
    }
    m.segments_.push_back(seg);
    parent = static_cast<int>(m.segments_.size()) - 1;
    pending = Pose();
  }
  *end = pending;
  return parent;
}

void ModelBuilder::CompileTreeJoint(const JointSpec& spec, int joint_index) {
  Model& m = *model_;
  Joint& joint = m.joints_[joint_index];
  const Body& b1 = m.bodies_[joint.body1];
  const Pose start = b1.in_segment * spec.frame1;
  int last = b1.segment;
  Pose end;
  if (spec.quaternion) {
    Segment seg;
    seg.parent = last;
    seg.placement = start;
    seg.motion = SegmentMotion::kFree;
    seg.drive = SegmentDrive::kDof;
    seg.joint = joint_index;
    seg.q_index = m.nq_;
    seg.v_index = m.nv_;
    const auto& init = spec.quaternion_initial;
    const Eigen::Quaterniond quat = init.orientation.normalized();
    const Vec3 v_body = quat.toRotationMatrix().transpose() * init.velocity;
    const double q0[7] = {init.position.x(), init.position.y(), init.position.z(), quat.w(), quat.x(), quat.y(),
                          quat.z()};
    const double v0[6] = {init.angular_velocity.x(), init.angular_velocity.y(), init.angular_velocity.z(),
                          v_body.x(), v_body.y(), v_body.z()};
    m.initial_q_.insert(m.initial_q_.end(), q0, q0 + 7);
    m.initial_v_.insert(m.initial_v_.end(), v0, v0 + 6);
    m.nq_ += 7;
    m.nv_ += 6;
    m.has_quaternions_ = true;
    m.segments_.push_back(seg);
    last = static_cast<int>(m.segments_.size()) - 1;
    joint.first_segment = last;
    end = Pose();
  } else {
    const int first_new = static_cast<int>(m.segments_.size());
    last = AppendChain(spec, joint_index, last, start, /*ghost=*/false, &end);
    if (last == b1.segment) {  // no moving transformation: a fixed joint gets a fixed segment
      Segment seg;
      seg.parent = last;
      seg.placement = start * end;
      seg.drive = SegmentDrive::kNone;
      seg.joint = joint_index;
      m.segments_.push_back(seg);
      last = first_new;
      end = Pose();
    }
    joint.first_segment = first_new;
  }
  joint.last_segment = last;
  joint.end_offset = end;
  Body& b2 = m.bodies_[joint.body2];
  b2.segment = last;
  b2.in_segment = end * spec.frame2.Inverse();
}

void ModelBuilder::CompileCutJoint(const JointSpec& spec, int joint_index) {
  Model& m = *model_;
  Joint& joint = m.joints_[joint_index];
  if (spec.convel) {
    const std::string where = Where(spec.origin) + "joint '" + spec.name + "': ";
    for (const Vec3* axis : {&spec.convel_axis1, &spec.convel_axis2})
      if (!(axis->norm() > 0.0)) throw InputError(where + "shaft axis must be non-zero");
    joint.is_cut = joint.convel = true;
    joint.cv_point1 = spec.frame1.p;
    joint.cv_point2 = spec.frame2.p;
    joint.cv_axis1 = spec.convel_axis1.normalized();
    joint.cv_axis2 = spec.convel_axis2.normalized();
    joint.cv_reference1 = spec.convel_reference1;
    joint.cv_reference2 = spec.convel_reference2;
    ++m.num_cut_joints_;
    return;
  }
  if (spec.quaternion)
    throw InputError(Where(spec.origin) + "joint '" + spec.name +
                     "': a quaternion joint cannot close a loop (it constrains nothing)");
  const Body& b1 = m.bodies_[joint.body1];
  const Pose start = b1.in_segment * spec.frame1;
  Pose end;
  int last = AppendChain(spec, joint_index, b1.segment, start, /*ghost=*/true, &end);
  if (last == b1.segment) end = start * end;
  joint.is_cut = true;
  joint.last_segment = last;
  joint.end_offset = end;
  joint.body2_attachment = spec.frame2;
  ++m.num_cut_joints_;
}

std::shared_ptr<const Model> ModelBuilder::Build() {
  if (built_) throw std::logic_error("ModelBuilder::Build() called twice");
  built_ = true;
  Model& m = *model_;
  for (std::size_t j = 0; j < joint_specs_.size(); ++j) {
    Joint joint;
    joint.name = joint_specs_[j].name;
    joint.body1 = m.FindBody(joint_specs_[j].body1);
    joint.body2 = m.FindBody(joint_specs_[j].body2);
    joint.origin = joint_specs_[j].origin;
    m.joint_index_.emplace(joint.name, static_cast<int>(m.joints_.size()));
    m.joints_.push_back(joint);
  }
  // Spanning tree: as if the joints were swept in file order until nothing
  // new is placed (a joint is taken when its body 1 is placed and its body 2
  // is not), without the sweeps: each joint waits, keyed by (sweep, file
  // position), for the first sweep that reaches it after its body 1 is placed.
  // A chain written leaf first took one sweep per joint (quadratic).
  std::vector<bool> placed(m.bodies_.size(), false), used(joint_specs_.size(), false);
  std::vector<std::vector<int>> joints_from(m.bodies_.size());  // joints by body 1, in file order
  for (std::size_t j = 0; j < joint_specs_.size(); ++j)
    if (!joint_specs_[j].convel) joints_from[m.joints_[j].body1].push_back(static_cast<int>(j));
  using Visit = std::pair<long, int>;  // (sweep, joint)
  std::priority_queue<Visit, std::vector<Visit>, std::greater<>> waiting;
  auto place = [&](int body, long sweep, int position) {  // placed at `position` of sweep `sweep`
    placed[body] = true;
    for (const int j : joints_from[body]) waiting.emplace(j > position ? sweep : sweep + 1, j);
  };
  place(0, 0, -1);
  while (!waiting.empty()) {
    const auto [sweep, j] = waiting.top();
    waiting.pop();
    const int body2 = m.joints_[j].body2;
    if (placed[body2]) continue;
    CompileTreeJoint(joint_specs_[j], j);
    used[j] = true;
    place(body2, sweep, j);
  }
  for (std::size_t b = 1; b < m.bodies_.size(); ++b) {
    if (placed[b]) continue;
    std::string hint;
    for (const auto& joint : m.joints_)
      if (joint.body2 == static_cast<int>(b) || joint.body1 == static_cast<int>(b))
        hint = " (joint '" + joint.name + "' uses it, but a chain of joints from Base0 must reach it as body 2)";
    throw InputError(Where(m.bodies_[b].origin) + "body '" + m.bodies_[b].name + "' is not connected to Base0" +
                     (hint.empty() ? " (no joint places it)" : hint));
  }
  for (std::size_t j = 0; j < joint_specs_.size(); ++j)
    if (!used[j]) CompileCutJoint(joint_specs_[j], static_cast<int>(j));
  // Bodies lend their inertia to the segment they ride on.
  for (const Body& body : m.bodies_) {
    if (body.segment == kGround) continue;
    const Pose& P = body.in_segment;
    m.segments_[body.segment].inertia +=
        SpatialInertia(body.mass, P * body.com, P.R * body.inertia * P.R.transpose());
  }
  CheckRotationsCarryInertia(m);
  m.sliding_ = FindSlidingStructure(m, &m.not_sliding_);
  return std::shared_ptr<const Model>(model_.release());
}

}  // namespace mechflow::mech
