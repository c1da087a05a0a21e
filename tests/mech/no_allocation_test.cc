// Evaluating a mechanism allocates nothing once set up (house rule: no
// allocation in the right-hand side). Eigen allocates through malloc, not
// operator new, so this test counts malloc itself (tests/malloc_counter.h).

#include <gtest/gtest.h>

#include "mech/frictional_force.h"
#include "mech/mechanism.h"
#include "tests/malloc_counter.h"
#include "tests/mech/mech_test_util.h"

namespace mechflow::mech {
namespace {

using testing::Et;
using T = TransformType;

long CountEvaluations(const Mechanism& mech) {
  MechanismWorkspace ws(mech);
  std::vector<double> x(mech.num_states()), xdot(mech.num_states()), modes(mech.num_modes());
  InitialState(mech, {}, x, modes, &ws);
  ws.want_reactions = true;
  EvaluateMechanism(mech, 0.0, x, {}, modes, &ws, xdot);  // warm
  g_calls = 0;
  g_counting = true;
  for (int i = 0; i < 100; ++i) {
    x[0] += 1e-3;
    EvaluateMechanism(mech, 0.01 * i, x, {}, modes, &ws, xdot);
    if (!mech.constraints().empty()) {
      std::span<double> q(x.data(), mech.model().nq()), v(x.data() + mech.model().nq(), mech.model().nv());
      ProjectPositions(mech.model(), mech.constraints(), 0.0, q, v, 1e-12, 5, &ws.kin, &ws.constraint);
      ProjectVelocities(mech.model(), mech.constraints(), 0.0, q, v, &ws.kin, &ws.constraint);
    }
    JointReaction(mech, ws, 0);
  }
  g_counting = false;
  return g_calls.load();
}

TEST(MechNoAllocationTest, TheCounterSeesEigenAllocations) {
  g_calls = 0;
  g_counting = true;
  Eigen::VectorXd v(100);
  v.setZero();
  g_counting = false;
  EXPECT_GE(g_calls.load(), 1) << "the malloc replacement is not in effect; the other tests would prove nothing";
}

TEST(MechNoAllocationTest, TreeEvaluationAllocatesNothing) {
  Mechanism mech(testing::MixedTree(), {}, {});
  EXPECT_EQ(CountEvaluations(mech), 0);
}

TEST(MechNoAllocationTest, LoopEvaluationAndProjectionAllocateNothing) {
  ModelBuilder m;
  m.AddBody(testing::Box("Crank", 0.3, {0.01, 0.15, 0.01}, Vec3(0, 0.15, 0)));
  m.AddBody(testing::Box("Rod", 0.8, {0.01, 0.4, 0.01}, Vec3(0, 0.4, 0)));
  m.AddBody(testing::Box("Rocker", 0.6, {0.01, 0.3, 0.01}, Vec3(0, 0.3, 0)));
  m.AddJoint(testing::ChainJoint("j1", "Base0", "Crank", {Et(T::kRv, Vec3::UnitX(), 1.2, 2.0)}));
  m.AddJoint(testing::ChainJoint("j2", "Crank", "Rod", {Et(T::kTc, Vec3::UnitY(), 0.3), Et(T::kRv, Vec3::UnitX(), -1.0)}));
  m.AddJoint(testing::ChainJoint("j3", "Base0", "Rocker", {Et(T::kTc, Vec3::UnitY(), 0.7), Et(T::kRv, Vec3::UnitX(), 1.9)}));
  JointSpec close = testing::ChainJoint("j4", "Rod", "Rocker", {Et(T::kTc, Vec3::UnitY(), 0.8), Et(T::kRv, Vec3::UnitX())});
  close.frame2 = Pose::Translation(Vec3(0, 0.6, 0));
  m.AddJoint(close);
  Mechanism mech(m.Build(), {}, {});
  EXPECT_EQ(CountEvaluations(mech), 0);
}

TEST(MechNoAllocationTest, ExactStickHoldsAllocateNothing) {
  // two exact holds, stuck (the tree starts at rest): their probe passes and
  // the solve for the holding forces run in every evaluation
  auto model = testing::MixedTree();
  ASSERT_GE(model->dofs().size(), 2u);
  FrictionalParameters p;
  p.friction = 1e6;  // never lets go
  p.exact_stick = true;
  std::vector<std::unique_ptr<ForceElement>> elements;
  elements.push_back(std::make_unique<FrictionalForce>("hold0", "", model->dofs()[0], p));
  elements.push_back(std::make_unique<FrictionalForce>("hold1", "", model->dofs()[1], p));
  Mechanism mech(model, std::move(elements), {});
  {
    MechanismWorkspace ws(mech);
    std::vector<double> x(mech.num_states()), modes(mech.num_modes());
    InitialState(mech, {}, x, modes, &ws);
    EvaluateMechanism(mech, 0.0, x, {}, modes, &ws, {});
    ASSERT_EQ(ws.stick.stuck.size(), 2u) << "the holds must be stuck for this test to mean anything";
  }
  EXPECT_EQ(CountEvaluations(mech), 0);
}

}  // namespace
}  // namespace mechflow::mech
