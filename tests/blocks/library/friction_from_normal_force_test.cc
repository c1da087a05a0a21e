// friction_from_normal_force: values at chosen (N, v) against the law written
// out here independently of mech/friction_law.cc, no dry friction for a
// pulling N, the force opposing v, and parameter checks.

#include <algorithm>
#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "blocks/library/friction_from_normal_force.h"

#include "tests/blocks/block_test_util.h"

namespace mechflow::blocks {
namespace {

using testing::Blocks;
using testing::MakeBlock;
using testing::MakeError;
using testing::Num;
using testing::Options;
using testing::Simulate;

// mu_s = 0.6, mu_d = 0.4, v_s = 0.01 m/s, c_visc = 2 N s/m, v_reg = 1e-3 m/s.
double Law(double n, double v) {
  const double mu = 0.4 + (0.6 - 0.4) * std::exp(-(std::abs(v) / 0.01) * (std::abs(v) / 0.01));
  return -(mu * std::max(n, 0.0) * std::tanh(v / 1e-3) + 2 * v);
}

// F for constant inputs N and v, from a one-instant run of the block.
double Friction(double n, double v) {
  const auto run = Simulate(Blocks(MakeBlock("constant", "N", {{"value", Num(n)}}),
                                   MakeBlock("constant", "v", {{"value", Num(v)}}),
                                   MakeBlock("friction_from_normal_force", "f",
                                             {{"mu_static", "0.6"},
                                              {"mu_dynamic", "0.4"},
                                              {"stribeck_velocity", "0.01"},
                                              {"viscous", "2"},
                                              {"regularisation_velocity", "1e-3"}})),
                            {{"N", "f.N"}, {"v", "f.v"}}, {"f.F"}, Options(0.1, 0.1));
  EXPECT_TRUE(run.outcome.ok) << run.outcome.failure;
  return run.Column("f.F").back();
}

TEST(FrictionFromNormalForceTest, ValuesFollowTheLaw) {
  struct Point {
    double n, v;
  };
  // sliding fast (mu ~ mu_d), near the Stribeck velocity, in the
  // regularisation zone, at rest, with either sign of v
  const Point points[] = {{100, 0.5}, {100, -0.5}, {50, 0.01}, {50, -0.005}, {10, 2e-4}, {10, 0.0}, {0, 0.3}};
  for (const Point& p : points) {
    // the same formula in the same order of operations: equal to rounding
    EXPECT_NEAR(Friction(p.n, p.v), Law(p.n, p.v), 1e-12 * (1 + std::abs(Law(p.n, p.v))))
        << "N = " << p.n << ", v = " << p.v;
  }
  // hand-checked anchors: fast sliding is mu_d N plus the viscous term
  EXPECT_NEAR(Friction(100, 0.5), -(0.4 * 100 + 2 * 0.5), 1e-9);
  EXPECT_EQ(Friction(10, 0.0), 0.0);
}

TEST(FrictionFromNormalForceTest, PullingNormalForceGivesNoDryFriction) {
  // only the viscous term remains
  EXPECT_NEAR(Friction(-50, 0.1), -2 * 0.1, 1e-15);
  EXPECT_NEAR(Friction(-50, -0.02), 2 * 0.02, 1e-15);
}

TEST(FrictionFromNormalForceTest, ForceOpposesTheVelocity) {
  for (const double v : {-1.0, -0.01, -1e-5, 1e-5, 0.01, 1.0}) {
    const double f = Friction(20, v);
    EXPECT_LT(f * v, 0.0) << "v = " << v;
  }
}

TEST(FrictionFromNormalForceTest, PortsAndFeedthrough) {
  const auto f = MakeBlock("friction_from_normal_force", "f", {{"mu_static", "0.5"}, {"mu_dynamic", "0.3"}});
  ASSERT_EQ(f->num_inputs(), 2);
  EXPECT_EQ(f->input_port(0).name, "N");
  EXPECT_EQ(f->input_port(1).name, "v");
  EXPECT_EQ(f->output_port(0).name, "F");
  EXPECT_EQ(f->output_port(1).name, "sliding");
  EXPECT_TRUE(f->HasFeedthrough(0, 0));
  EXPECT_TRUE(f->HasFeedthrough(1, 0));
  EXPECT_TRUE(f->HasFeedthrough(0, 1));
  EXPECT_FALSE(f->HasFeedthrough(1, 1));  // the sliding force does not read v
}

// sliding = mu_d max(N, 0), whatever v is.
TEST(FrictionFromNormalForceTest, SlidingForceIsMuDynamicTimesN) {
  const testing::Run run = Simulate(Blocks(MakeBlock("friction_from_normal_force", "f",
                                            {{"mu_static", "0.5"}, {"mu_dynamic", "0.3"}}),
                                  MakeBlock("sine", "n", {{"amplitude", "10"}, {"frequency", "1"}}),
                                  MakeBlock("constant", "v", {{"value", "2"}})),
                           {{"n.y", "f.N"}, {"v.y", "f.v"}}, {"n.y", "f.sliding"}, Options(1.0, 0.01));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto n = run.Column("n.y"), s = run.Column("f.sliding");
  for (std::size_t i = 0; i < n.size(); ++i) EXPECT_NEAR(s[i], 0.3 * std::max(n[i], 0.0), 1e-12);
}

// normal="bilateral": a guide pressed either way, friction from |N|; a
// unilateral block fed a pulling N says so after the run (the largest pull and
// when), and does not for rounding about a zero.
TEST(FrictionFromNormalForceTest, TheNormalRuleIsAChoiceAndAPullIsReported) {
  const auto run = [](const char* normal, const char* offset) {
    return Simulate(Blocks(MakeBlock("friction_from_normal_force", "f",
                                     {{"mu_static", "0.5"}, {"mu_dynamic", "0.3"}, {"normal", normal}}),
                           MakeBlock("sine", "n", {{"amplitude", "10"}, {"frequency", "1"}, {"bias", offset}}),
                           MakeBlock("constant", "v", {{"value", "2"}})),
                    {{"n.y", "f.N"}, {"v.y", "f.v"}}, {"n.y", "f.sliding", "f.F"}, Options(1.0, 0.01));
  };
  const testing::Run bilateral = run("bilateral", "0");
  ASSERT_TRUE(bilateral.outcome.ok) << bilateral.outcome.failure;
  const auto n = bilateral.Column("n.y"), s = bilateral.Column("f.sliding"), f = bilateral.Column("f.F");
  for (std::size_t i = 0; i < n.size(); ++i) {
    EXPECT_NEAR(s[i], 0.3 * std::abs(n[i]), 1e-12);
    EXPECT_NEAR(f[i], -0.3 * std::abs(n[i]), 1e-9);  // v = 2 m/s: mu_d, tanh = 1
  }
  const auto& pressed_both_ways = dynamic_cast<const FrictionFromNormalForceBlock&>(bilateral.diagram->block(0));
  EXPECT_EQ(pressed_both_ways.PullingWarning(bilateral.sim->context(), 0), "");

  const testing::Run unilateral = run("unilateral", "0");
  const auto& pulled = dynamic_cast<const FrictionFromNormalForceBlock&>(unilateral.diagram->block(0));
  const std::string warning = pulled.PullingWarning(unilateral.sim->context(), 0);
  EXPECT_EQ(warning.rfind("block 'f' (friction_from_normal_force, normal=\"unilateral\") receives a "
                          "pulling normal force (N = -10 N at t = 0.75 s, the largest pull)", 0), 0u)
      << warning;
  EXPECT_THAT(warning, ::testing::HasSubstr("set normal=\"bilateral\""));
  // N = 10 (1 + sin) >= 0 touches 0 at t = 0.75: at most rounding below it
  const testing::Run touching = run("unilateral", "10");
  EXPECT_EQ(dynamic_cast<const FrictionFromNormalForceBlock&>(touching.diagram->block(0))
                .PullingWarning(touching.sim->context(), 0), "");
}

TEST(FrictionFromNormalForceTest, FactoryRejectsUnusableParameters) {
  const testing::ParamTexts ok = {{"mu_static", "0.5"}, {"mu_dynamic", "0.3"}};
  auto with = [&](const char* name, const char* value) {
    testing::ParamTexts p = ok;
    p[name] = value;
    return MakeError("friction_from_normal_force", p);
  };
  EXPECT_EQ(with("mu_static", "-0.1"), "mu_static must be >= 0");
  EXPECT_EQ(with("mu_dynamic", "-1"), "mu_dynamic must be >= 0");
  EXPECT_EQ(with("stribeck_velocity", "0"), "stribeck_velocity must be > 0");
  EXPECT_EQ(with("viscous", "-2"), "viscous must be >= 0");
  EXPECT_EQ(with("regularisation_velocity", "0"), "regularisation_velocity must be > 0");
  EXPECT_EQ(with("viscous", "inf"), "'viscous' must be a finite number, got inf");
  EXPECT_EQ(with("normal", "both"),
            "normal must be \"unilateral\" (a contact that only pushes: max(N, 0)) or \"bilateral\" (a guide "
            "holding the body both ways: |N|), not \"both\"");
}

}  // namespace
}  // namespace mechflow::blocks
