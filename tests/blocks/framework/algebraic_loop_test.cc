// Algebraic loops: cycles of direct feedthrough are scheduled as one entry
// and solved by Newton on their tear signals at every evaluation. Answers are
// closed forms; a loop with no solution fails the run naming its hops.

#include "blocks/framework/algebraic_loop.h"

#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "blocks/framework/diagram.h"
#include "tests/blocks/block_test_util.h"

namespace mechflow::blocks::testing {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

// s = 1 + k s, one loop through a gain and a sum: s = 1 / (1 - k).
testing::Run LinearLoop(double k) {
  return Simulate(Blocks(MakeBlock("constant", "c", {{"value", "1"}}), MakeBlock("gain", "a", {{"k", Num(k)}}),
                         MakeBlock("sum", "s")),
                  {{"c.y", "s.u1"}, {"a.y", "s.u2"}, {"s.y", "a.u"}}, {"s.y", "a.y"}, Options(1.0, 0.5));
}

TEST(AlgebraicLoopTest, LinearLoopIsOneScheduleEntry) {
  const testing::Run run = LinearLoop(0.5);
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  ASSERT_EQ(run.diagram->loops().size(), 1u);
  const AlgebraicLoop& loop = run.diagram->loops()[0];
  EXPECT_EQ(loop.num_unknowns(), 1);  // one tear cuts a simple cycle
  EXPECT_THAT(loop.description(), AllOf(HasSubstr("a.y -> s.u2 (feeds s.y directly)"),
                                        HasSubstr("s.y -> a.u (feeds a.y directly)")));
  int loop_entries = 0;
  for (const OutputNode& node : run.diagram->schedule()) loop_entries += node.loop >= 0;
  EXPECT_EQ(loop_entries, 1);
  for (const double s : run.Column("s.y")) EXPECT_NEAR(s, 2.0, 1e-12);
  for (const double a : run.Column("a.y")) EXPECT_NEAR(a, 1.0, 1e-12);
  // Linear: once the Jacobian is known every solve takes at most one step.
  const LoopStats& stats = loop.stats(run.sim->context());
  EXPECT_GT(stats.solves, 0);
  EXPECT_LE(stats.iterations, stats.solves);
  EXPECT_EQ(stats.jacobians, 1);
}

TEST(AlgebraicLoopTest, NegativeLoopGain) {
  const testing::Run run = LinearLoop(-3.0);  // s = 1 - 3 s
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  for (const double s : run.Column("s.y")) EXPECT_NEAR(s, 0.25, 1e-12);
}

// s = 1 - 0.2 s^2 through a product: the positive root (sqrt(1.8) - 1) / 0.4
// is the one Newton reaches from 0.
TEST(AlgebraicLoopTest, NonlinearLoopConverges) {
  const testing::Run run = Simulate(
      Blocks(MakeBlock("constant", "c", {{"value", "1"}}), MakeBlock("product", "p"),
             MakeBlock("gain", "g", {{"k", "-0.2"}}), MakeBlock("sum", "s")),
      {{"s.y", "p.u1"}, {"s.y", "p.u2"}, {"p.y", "g.u"}, {"c.y", "s.u1"}, {"g.y", "s.u2"}}, {"s.y"},
      Options(1.0, 0.5));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const double root = (std::sqrt(1.8) - 1.0) / 0.4;
  for (const double s : run.Column("s.y")) EXPECT_NEAR(s, root, 1e-10 * root);
}

// x' = -s with s = x + 0.5 s, i.e. s = 2 x: x = exp(-2 t). The loop is solved
// at every right-hand side, not delayed by a step.
TEST(AlgebraicLoopTest, LoopInsideTheDynamics) {
  const testing::Run run = Simulate(Blocks(MakeBlock("integrator", "x", {{"initial", "1"}}),
                                  MakeBlock("gain", "neg", {{"k", "-1"}}), MakeBlock("gain", "h", {{"k", "0.5"}}),
                                  MakeBlock("sum", "s")),
                           {{"x.y", "s.u1"}, {"h.y", "s.u2"}, {"s.y", "h.u"}, {"s.y", "neg.u"}, {"neg.y", "x.u"}},
                           {"x.y", "s.y"}, Options(2.0, 0.1));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto t = run.Time(), x = run.Column("x.y"), s = run.Column("s.y");
  for (std::size_t i = 0; i < t.size(); ++i) {
    EXPECT_NEAR(x[i], std::exp(-2.0 * t[i]), 1e-8);
    EXPECT_NEAR(s[i], 2.0 * x[i], 1e-11);
  }
}

// x = 0.5 y + 1, y = 0.25 x + 2: two sums and two gains in one component.
TEST(AlgebraicLoopTest, CoupledPairOfSignals) {
  const testing::Run run = Simulate(Blocks(MakeBlock("constant", "one", {{"value", "1"}}),
                                  MakeBlock("constant", "two", {{"value", "2"}}),
                                  MakeBlock("gain", "gx", {{"k", "0.5"}}), MakeBlock("gain", "gy", {{"k", "0.25"}}),
                                  MakeBlock("sum", "x"), MakeBlock("sum", "y")),
                           {{"gx.y", "x.u1"}, {"one.y", "x.u2"}, {"gy.y", "y.u1"}, {"two.y", "y.u2"},
                            {"y.y", "gx.u"}, {"x.y", "gy.u"}},
                           {"x.y", "y.y"}, Options(1.0, 0.5));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  EXPECT_NEAR(run.Column("x.y").back(), 2.0 / 0.875, 1e-11);
  EXPECT_NEAR(run.Column("y.y").back(), 0.25 * 2.0 / 0.875 + 2.0, 1e-11);
}

// y = y + 1 has no solution: the run fails at the start, naming the loop.
TEST(AlgebraicLoopTest, LoopWithoutSolutionNamesItsHops) {
  const testing::Run run = LinearLoop(1.0);
  ASSERT_FALSE(run.outcome.ok);
  EXPECT_THAT(run.outcome.failure,
              AllOf(HasSubstr("algebraic loop through"), HasSubstr("a.y -> s.u2 (feeds s.y directly)"),
                    HasSubstr("no unique solution")));
}

// A block feeding itself: y = 1 + s y through one sum (signs "+" and s).
// Its input reads a copy of its output that the solver sets, so the loop is
// solved like any other (y = 1 - y gives 0.5) or fails (y = 1 + y has no
// solution) -- it once gave 0 and 2 and exited 0.
testing::Run SelfLoop(const std::string& signs) {
  return Simulate(Blocks(MakeBlock("constant", "c", {{"value", "1"}}), MakeBlock("sum", "s", {{"signs", signs}})),
                  {{"c.y", "s.u1"}, {"s.y", "s.u2"}}, {"s.y"}, Options(1.0, 0.5));
}

TEST(AlgebraicLoopTest, OneBlockLoopsAreSolvedOrFail) {
  const testing::Run half = SelfLoop("+-");
  ASSERT_TRUE(half.outcome.ok) << half.outcome.failure;
  ASSERT_EQ(half.diagram->loops().size(), 1u);
  for (const double y : half.Column("s.y")) EXPECT_NEAR(y, 0.5, 1e-12);
  const testing::Run none = SelfLoop("++");
  ASSERT_FALSE(none.outcome.ok);
  EXPECT_THAT(none.outcome.failure,
              AllOf(HasSubstr("algebraic loop through s.y:\n  s.y -> s.u2 (feeds s.y directly)"),
                    HasSubstr("could not be solved at t = 0: it has no unique solution"),
                    HasSubstr("largest residual 1")));
  EXPECT_EQ(none.outcome.t_reached, 0.0);
}

// A loop whose Newton iteration runs away (s = 1 + s^2 has no real root).
TEST(AlgebraicLoopTest, DivergingLoopFailsClearly) {
  const testing::Run run = Simulate(
      Blocks(MakeBlock("constant", "c", {{"value", "1"}}), MakeBlock("product", "p"), MakeBlock("sum", "s")),
      {{"s.y", "p.u1"}, {"s.y", "p.u2"}, {"c.y", "s.u1"}, {"p.y", "s.u2"}}, {"s.y"}, Options(1.0, 0.5));
  ASSERT_FALSE(run.outcome.ok);
  EXPECT_THAT(run.outcome.failure, AllOf(HasSubstr("algebraic loop through"), HasSubstr("could not be solved")));
}

// A brake shoe pressed by P, whose lining's friction F = mu N (sliding at
// v = 1 m/s) pulls it further on through lever arms c / b: N = P + (c / b) mu N.
// The loop map's derivative is mu c / b: below 1, N = P / (1 - mu c / b); above
// (self-locking), no N balances it. P starts to grow at t = 0.5.
testing::Run Brake(double c_over_b) {
  return Simulate(Blocks(MakeBlock("ramp", "P", {{"slope", "100"}, {"start", "0.5"}}),
                         MakeBlock("constant", "v", {{"value", "1"}}),
                         MakeBlock("friction_from_normal_force", "lining", {{"mu_static", "0.5"}, {"mu_dynamic", "0.5"}}),
                         MakeBlock("gain", "arm", {{"k", Num(-c_over_b)}}), MakeBlock("sum", "N"),
                         MakeBlock("integrator", "work")),
                  {{"P.y", "N.u1"}, {"arm.y", "N.u2"}, {"N.y", "lining.N"}, {"v.y", "lining.v"},
                   {"lining.F", "arm.u"}, {"N.y", "work.u"}},
                  {"P.y", "N.y"}, Options(1.0, 0.1));
}

TEST(AlgebraicLoopTest, ASelfLockingBrakeHasNoSolutionAndSaysItsGain) {
  const testing::Run holds = Brake(1.0);  // gain 0.5
  ASSERT_TRUE(holds.outcome.ok) << holds.outcome.failure;
  const auto p = holds.Column("P.y"), n = holds.Column("N.y");
  for (std::size_t i = 0; i < n.size(); ++i) EXPECT_NEAR(n[i], 2 * p[i], 1e-8 * (1 + p[i]));

  const testing::Run locks = Brake(3.0);  // gain 1.5 from t = 0.5 on
  ASSERT_FALSE(locks.outcome.ok);
  EXPECT_THAT(locks.outcome.failure,
              AllOf(HasSubstr("algebraic loop through"), HasSubstr("lining.F -> arm.u (feeds arm.y directly)"),
                    HasSubstr("could not be solved at t = 0.5"), HasSubstr("no solution: the loop returns more"),
                    HasSubstr("reached 1.5 > 1")));
  EXPECT_THAT(locks.outcome.failure, ::testing::Not(HasSubstr("step size")));
  EXPECT_THAT(locks.outcome.failure, ::testing::Not(HasSubstr("no convergence")));
  EXPECT_EQ(locks.Column("N.y").size(), 6u);  // the rows up to t = 0.5 stand
  EXPECT_NEAR(locks.outcome.t_reached, 0.5, 1e-6);
}

}  // namespace
}  // namespace mechflow::blocks::testing
