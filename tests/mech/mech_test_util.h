#pragma once
// Small mechanisms built in code, shared by the tests of mech/.

#include <memory>
#include <random>
#include <string>

#include "mech/model_builder.h"

namespace mechflow::mech::testing {

inline BodySpec Box(const std::string& name, double mass, const Vec3& half_sizes, const Vec3& com = Vec3::Zero()) {
  BodySpec b;
  b.name = name;
  b.mass = mass;
  b.com = com;
  const Vec3 s = 2.0 * half_sizes;
  b.inertia = (mass / 12.0) * Vec3(s.y() * s.y() + s.z() * s.z(), s.x() * s.x() + s.z() * s.z(),
                                   s.x() * s.x() + s.y() * s.y())
                                  .asDiagonal();
  return b;
}

inline TransformSpec Et(TransformType type, const Vec3& axis, double value = 0.0, double rate = 0.0) {
  TransformSpec et;
  et.type = type;
  et.axis = axis;
  et.value = value;
  et.rate = rate;
  return et;
}

inline JointSpec ChainJoint(const std::string& name, const std::string& b1, const std::string& b2,
                            std::vector<TransformSpec> chain) {
  JointSpec j;
  j.name = name;
  j.body1 = b1;
  j.body2 = b2;
  j.chain = std::move(chain);
  return j;
}

// A spatial tree exercising every segment kind: a 6-DOF Cardan body, a
// revolute with an offset and tilted axis, a prismatic, a quaternion joint and
// a branch.
inline std::shared_ptr<const Model> MixedTree() {
  ModelBuilder b;
  b.AddBody(Box("A", 2.0, {0.3, 0.2, 0.1}, {0.05, -0.02, 0.01}));
  b.AddBody(Box("B", 1.5, {0.1, 0.4, 0.1}, {0.0, 0.2, 0.0}));
  b.AddBody(Box("C", 0.7, {0.1, 0.1, 0.3}));
  b.AddBody(Box("D", 1.1, {0.2, 0.1, 0.15}, {0.01, 0.02, 0.03}));
  b.AddBody(Box("E", 0.4, {0.05, 0.3, 0.05}, {0.0, 0.1, 0.0}));
  using T = TransformType;
  b.AddJoint(ChainJoint("jA", "Base0", "A",
                        {Et(T::kTv, Vec3::UnitX()), Et(T::kTv, Vec3::UnitY()), Et(T::kTv, Vec3::UnitZ()),
                         Et(T::kRv, Vec3::UnitX()), Et(T::kRv, Vec3::UnitY()), Et(T::kRv, Vec3::UnitZ())}));
  b.AddJoint(ChainJoint("jB", "A", "B",
                        {Et(T::kTc, Vec3(0.1, 0.2, 0.3), 1.0), Et(T::kRc, Vec3::UnitY(), 0.3),
                         Et(T::kRv, Vec3(1.0, 1.0, 0.0))}));
  b.AddJoint(ChainJoint("jC", "B", "C", {Et(T::kTc, Vec3::UnitY(), 0.8), Et(T::kTv, Vec3(0.0, 0.3, 1.0))}));
  JointSpec q;
  q.name = "jD";
  q.body1 = "A";
  q.body2 = "D";
  q.quaternion = true;
  q.frame1 = Pose::Translation(Vec3(-0.3, 0.0, 0.1));
  b.AddJoint(q);
  b.AddJoint(ChainJoint("jE", "D", "E", {Et(T::kRv, Vec3::UnitZ()), Et(T::kTc, Vec3::UnitX(), 0.2)}));
  return b.Build();
}

// Random coordinates (quaternions normalised) and velocities.
inline void RandomState(const Model& model, std::mt19937* rng, std::vector<double>* q, std::vector<double>* v) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  q->resize(model.nq());
  v->resize(model.nv());
  for (double& x : *q) x = u(*rng);
  for (double& x : *v) x = u(*rng);
  for (const Segment& seg : model.segments()) {
    if (seg.motion != SegmentMotion::kFree) continue;
    Eigen::Map<Eigen::Vector4d> quat(q->data() + seg.q_index + 3);
    quat.normalize();
  }
}

}  // namespace mechflow::mech::testing
