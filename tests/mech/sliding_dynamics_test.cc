// The sliding model's shortcuts (mech/sliding_structure.h) against the
// general tree algorithms they replace: the same kinematics, and the same
// accelerations as the articulated-body algorithm, on a model with every
// kind of segment a sliding model may have.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "mech/dynamics.h"
#include "mech/sliding_structure.h"
#include "tests/mech/mech_test_util.h"

namespace mechflow::mech {
namespace {

using testing::Box;
using testing::ChainJoint;
using testing::Et;
using T = TransformType;

// s(t) = c t^3: a time-driven translation with a rate and an acceleration.
class Cubic final : public TimeFunction {
 public:
  explicit Cubic(double c) : c_(c) {}
  Jet Evaluate(double t) const override { return {c_ * t * t * t, 3 * c_ * t * t, 6 * c_ * t}; }

 private:
  double c_;
};

TransformSpec Timed(const Vec3& axis, double c) {
  TransformSpec et = Et(T::kTt, axis);
  et.function = std::make_shared<Cubic>(c);
  return et;
}

// A turned base, a carriage sliding along x and then (after a time-driven
// shift along an oblique axis) along y of that turned frame; on it a slide
// along z, turned about z first; a body welded to the carriage; a second
// branch on the ground along an oblique axis; an offset centre of mass.
std::shared_ptr<const Model> SlidingTree() {
  ModelBuilder b;
  b.AddBody(Box("A", 2.0, {0.3, 0.2, 0.1}, {0.05, -0.02, 0.01}));
  b.AddBody(Box("B", 1.5, {0.1, 0.4, 0.1}, {0.0, 0.2, 0.0}));
  b.AddBody(Box("C", 0.7, {0.1, 0.1, 0.3}));
  b.AddBody(Box("W", 0.4, {0.05, 0.3, 0.05}));
  b.AddJoint(ChainJoint("jA", "Base0", "A",
                        {Et(T::kTc, Vec3(0.1, 0.2, 0.3), 1.0), Et(T::kRc, Vec3::UnitZ(), 0.4),
                         Et(T::kTv, Vec3::UnitX(), 0.3, -0.2), Timed(Vec3(1.0, 1.0, 0.5), 0.7),
                         Et(T::kTv, Vec3::UnitY(), -0.1, 0.4)}));
  b.AddJoint(ChainJoint("jB", "A", "B",
                        {Et(T::kTc, Vec3::UnitY(), 0.8), Et(T::kRc, Vec3::UnitZ(), 0.7),
                         Et(T::kTv, Vec3::UnitZ(), 0.2, 0.1)}));
  b.AddJoint(ChainJoint("jC", "Base0", "C", {Et(T::kRc, Vec3::UnitX(), 0.2), Et(T::kTv, Vec3(0.0, 0.3, 1.0))}));
  JointSpec weld = ChainJoint("jW", "A", "W", {Et(T::kTc, Vec3::UnitX(), 0.5)});
  weld.frame2 = Pose::Rotation(AxisRotation(Vec3::UnitY(), 0.3));
  b.AddJoint(weld);
  return b.Build();
}

void ExpectNear(const Eigen::Ref<const Eigen::MatrixXd>& a, const Eigen::Ref<const Eigen::MatrixXd>& b,
                const std::string& what) {
  EXPECT_LT((a - b).cwiseAbs().maxCoeff(), 1e-13 * (1.0 + b.cwiseAbs().maxCoeff())) << what << "\n"
                                                                                    << a << "\nagainst\n"
                                                                                    << b;
}

TEST(SlidingDynamicsTest, ModelsThatOnlySlideAreFound) {
  const auto model = SlidingTree();
  ASSERT_NE(model->sliding(), nullptr) << model->not_sliding();
  const SlidingStructure& s = *model->sliding();
  // the mass each coordinate carries: A's x and y carry A, B and W; B's z carries B
  const double carried[] = {2.0 + 1.5 + 0.4, 2.0 + 1.5 + 0.4, 1.5, 0.7};
  for (int i = 0; i < 4; ++i) EXPECT_DOUBLE_EQ(s.coordinate_mass[i], carried[i]) << i;
  EXPECT_FALSE(testing::MixedTree()->sliding());
  EXPECT_NE(testing::MixedTree()->not_sliding().find("turns"), std::string::npos);

  ModelBuilder oblique;
  oblique.AddBody(Box("A", 1.0, {0.1, 0.1, 0.1}));
  oblique.AddJoint(ChainJoint("j", "Base0", "A", {Et(T::kTv, Vec3::UnitX()), Et(T::kTv, Vec3(1.0, 1.0, 0.0))}));
  const auto not_sliding = oblique.Build();
  EXPECT_FALSE(not_sliding->sliding());
  EXPECT_NE(not_sliding->not_sliding().find("not perpendicular"), std::string::npos) << not_sliding->not_sliding();
}

TEST(SlidingDynamicsTest, KinematicsAndAccelerationsAgreeWithTheTreeAlgorithms) {
  const auto model = SlidingTree();
  ASSERT_NE(model->sliding(), nullptr) << model->not_sliding();
  Kinematics fast(*model), tree(*model);
  DynamicsWorkspace fast_ws(*model), tree_ws(*model);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  std::vector<Vec6> external(model->segments().size());
  std::vector<double> tau(model->nv()), fast_vdot(model->nv()), tree_vdot(model->nv());
  for (int trial = 0; trial < 10; ++trial) {
    const double t = 0.1 * trial;
    std::vector<double> q, v;
    testing::RandomState(*model, &rng, &q, &v);
    UpdateKinematics(*model, t, q, v, &fast);
    UpdateKinematicsOfTree(*model, t, q, v, &tree);
    for (std::size_t i = 0; i < model->segments().size(); ++i) {
      const std::string at = "segment " + std::to_string(i);
      ExpectNear(fast.X[i].E, tree.X[i].E, at + " E");
      ExpectNear(fast.X[i].r, tree.X[i].r, at + " r");
      ExpectNear(fast.pose[i].R, tree.pose[i].R, at + " R");
      ExpectNear(fast.pose[i].p, tree.pose[i].p, at + " p");
      ExpectNear(fast.axis[i], tree.axis[i], at + " axis");
      ExpectNear(fast.velocity[i], tree.velocity[i], at + " velocity");
      ExpectNear(fast.bias[i], tree.bias[i], at + " bias");
    }
    for (int b = 0; b < model->num_bodies(); ++b) {
      const std::string at = "body " + model->bodies()[b].name;
      ExpectNear(fast.body_pose[b].R, tree.body_pose[b].R, at + " R");
      ExpectNear(fast.body_pose[b].p, tree.body_pose[b].p, at + " p");
      ExpectNear(fast.body_omega[b], tree.body_omega[b], at + " omega");
      ExpectNear(fast.body_velocity[b], tree.body_velocity[b], at + " velocity");
    }
    for (double& x : tau) x = u(rng);
    for (auto& f : external)
      for (int k = 0; k < 6; ++k) f(k) = u(rng);
    ForwardDynamics(*model, fast, tau, external, fast_vdot, &fast_ws);
    ArticulatedBodyDynamics(*model, tree, tau, external, tree_vdot, &tree_ws);
    ExpectNear(Eigen::Map<Eigen::VectorXd>(fast_vdot.data(), model->nv()),
               Eigen::Map<Eigen::VectorXd>(tree_vdot.data(), model->nv()), "v'");
    for (std::size_t i = 0; i < model->segments().size(); ++i)
      ExpectNear(fast_ws.acceleration[i], tree_ws.acceleration[i], "acceleration of segment " + std::to_string(i));
    for (int b = 0; b < model->num_bodies(); ++b)
      ExpectNear(PointAcceleration(*model, fast, fast_ws, b, Vec3(0.1, -0.2, 0.3)),
                 PointAcceleration(*model, tree, tree_ws, b, Vec3(0.1, -0.2, 0.3)),
                 "point acceleration on " + model->bodies()[b].name);
  }
}

}  // namespace
}  // namespace mechflow::mech
