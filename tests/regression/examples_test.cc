// The example diagrams in diagrams/examples/, each run and checked against an
// answer computed independently of the simulator (closed form or a piecewise
// analytic solution written out here).

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "blocks/solver/simulator.h"
#include "diagrams/loader.h"
#include "tests/numbers.h"

namespace mechflow {
namespace {

using mechflow::testing::kPi;

std::string Example(const std::string& name) {
  return std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/" + name;
}

struct ExampleRun {
  diagrams::LoadedDiagram loaded;
  std::unique_ptr<blocks::Simulator> sim;
  blocks::RunOutcome outcome;

  explicit ExampleRun(const std::string& example, const diagrams::LoadOptions& options = {})
      : loaded(diagrams::LoadDiagram(Example(example), options)) {
    sim = std::make_unique<blocks::Simulator>(*loaded.diagram, loaded.solver, loaded.logged);
    outcome = sim->Run();
  }
  const blocks::Results& results() const { return sim->results(); }
  std::vector<double> Column(const std::string& name) const {
    const int c = results().FindColumn(name);
    EXPECT_GE(c, 0) << "no column " << name;
    return c < 0 ? std::vector<double>() : results().Column(c);
  }
};

// x'' = -(c x + d v)/m from x(0) = x0, v(0) = 0: the underdamped closed form,
// for the diagram built from integrators and gains and for the one Lua block
// of damped_oscillator_lua.xml.
class DampedOscillatorTest : public ::testing::TestWithParam<const char*> {};

TEST_P(DampedOscillatorTest, MatchesClosedForm) {
  ExampleRun run(GetParam());
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const double m = 1000, f = 1, beta = 0.1, x0 = 0.5;
  const double c = 4 * kPi * kPi * f * f * m, d = 2 * beta * std::sqrt(m * c);
  const double w = std::sqrt(c / m), zeta = d / (2 * std::sqrt(m * c)), wd = w * std::sqrt(1 - zeta * zeta);
  const auto t = run.Column("time"), x = run.Column("x");
  ASSERT_EQ(t.size(), 1001u);
  EXPECT_DOUBLE_EQ(t.back(), 10.0);
  double max_error = 0;
  for (size_t i = 0; i < t.size(); ++i) {
    const double exact =
        std::exp(-zeta * w * t[i]) * (x0 * std::cos(wd * t[i]) + zeta * w * x0 / wd * std::sin(wd * t[i]));
    max_error = std::max(max_error, std::abs(x[i] - exact));
  }
  // the bound at rtol 1e-8
  EXPECT_LT(max_error, 1e-5);
}

INSTANTIATE_TEST_SUITE_P(Examples, DampedOscillatorTest,
                         ::testing::Values("damped_oscillator_blocks.xml", "damped_oscillator_lua.xml"));

// The Lua block computes (-c/m) x + (-d/m) v in the order the gains and the
// sum do, so the solver sees the same numbers and takes the same steps: the
// two runs agree to rounding, far inside the solver tolerance (atol 1e-10).
TEST(ExamplesTest, DampedOscillatorLuaBlockMatchesBlocksVersion) {
  ExampleRun lua("damped_oscillator_lua.xml");
  ExampleRun blocks("damped_oscillator_blocks.xml");
  ASSERT_TRUE(lua.outcome.ok) << lua.outcome.failure;
  ASSERT_TRUE(blocks.outcome.ok) << blocks.outcome.failure;
  const auto x_lua = lua.Column("x"), v_lua = lua.Column("v");
  const auto x_blocks = blocks.Column("x"), v_blocks = blocks.Column("v");
  ASSERT_EQ(x_lua.size(), x_blocks.size());
  double worst = 0;
  for (std::size_t i = 0; i < x_lua.size(); ++i)
    worst = std::max({worst, std::abs(x_lua[i] - x_blocks[i]), std::abs(v_lua[i] - v_blocks[i])});
  EXPECT_LT(worst, 1e-12);
  EXPECT_EQ(lua.sim->stats().rhs_evals, blocks.sim->stats().rhs_evals);
}

// Stiff Van der Pol, mu = 1000, over [0, 3000] (about two relaxation periods).
TEST(ExamplesTest, VanDerPolStiffFinishesInFewSteps) {
  ExampleRun run("van_der_pol_stiff.xml");
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto t = run.Column("time"), y1 = run.Column("y1");
  EXPECT_DOUBLE_EQ(t.back(), 3000.0);
  // the limit cycle of y1 stays within about [-2.01, 2.01]
  for (const double v : y1) EXPECT_LT(std::abs(v), 2.05);
  // Bound: BDF needs a few hundred steps per relaxation jump and takes steps
  // of seconds on the slow branches; 3000 steps leaves room for tolerance and
  // platform differences. An explicit method, limited by stability to
  // h < 2/|lambda| with lambda ~ -mu (y1^2 - 1) ~ -3000, needs over 4 million.
  EXPECT_LT(run.sim->stats().steps, 3000);
  // the relaxation period is about (3 - 2 ln 2) mu = 1614 s: y1 changes sign
  // (a jump) once near t ~ 807 and again near t ~ 1614 + 807
  int sign_changes = 0;
  for (size_t i = 1; i < y1.size(); ++i) sign_changes += (y1[i] > 0) != (y1[i - 1] > 0);
  EXPECT_EQ(sign_changes, 3);
}

// Free fall from h0 with restitution e: impact n happens at
// t1 = sqrt(2 h0 / g), t(n+1) = t(n) + 2 e^n v1 / g with v1 = g t1.
TEST(ExamplesTest, BouncingBallImpactTimesMatchClosedForm) {
  ExampleRun run("bouncing_ball_blocks.xml");
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const double g = 9.81, h0 = 10, e = 0.8;
  const auto& events = run.sim->events();
  ASSERT_GE(events.size(), 5u);
  double t_impact = std::sqrt(2 * h0 / g);
  const double v1 = g * t_impact;
  for (int n = 0; n < 5; ++n) {
    EXPECT_NEAR(events[n].time, t_impact, 1e-6) << "impact " << n + 1;
    EXPECT_EQ(run.loaded.diagram->block(events[n].block).name(), "v");
    t_impact += 2 * std::pow(e, n + 1) * v1 / g;
  }
  // the ball never goes (measurably) below ground
  for (const double h : run.Column("height")) EXPECT_GT(h, -1e-6);
}

// Piecewise-analytic stick-slip cycle for a Coulomb law (mass on a belt):
// stick at belt speed from x_d - D to x_s = x_d + D, where x_s = mu_s m g / k
// and x_d = mu_d m g / k, D = x_s - x_d; then a harmonic slip arc about x_d
// at w = sqrt(k/m), starting and ending at belt speed. Stick lasts 2 D / v_b,
// slip (pi + 2 atan(v_b / (w D))) / w.
TEST(ExamplesTest, StickSlipLimitCycleMatchesCoulombAnalysis) {
  diagrams::LoadOptions options;
  options.t_end = 10.0;
  ExampleRun run("stick_slip_blocks.xml", options);
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const double m = 1, k = 100, g = 9.81, vb = 0.1, mu_s = 0.6, mu_d = 0.4;
  const double w = std::sqrt(k / m), x_s = mu_s * m * g / k, x_d = mu_d * m * g / k, D = x_s - x_d;
  const double stick = 2 * D / vb, slip = (kPi + 2 * std::atan(vb / (w * D))) / w;
  ASSERT_NEAR(stick + slip, 0.8008, 1e-4);  // the figure quoted in the example's comment

  const auto t = run.Column("time"), x = run.Column("x"), v = run.Column("v");
  // slip starts when v - vb first drops below -threshold after a stick phase;
  // slip ends when it comes back above it. Interpolate the crossing times.
  const double threshold = 1e-3;
  std::vector<double> slip_start, slip_end;
  std::vector<double> x_at_slip_start;
  for (size_t i = 1; i < t.size(); ++i) {
    const double a = v[i - 1] - vb + threshold, b = v[i] - vb + threshold;
    if ((a >= 0) != (b >= 0)) {
      const double tc = t[i - 1] + (t[i] - t[i - 1]) * a / (a - b);
      (b < 0 ? slip_start : slip_end).push_back(tc);
      if (b < 0) x_at_slip_start.push_back(x[i - 1]);
    }
  }
  ASSERT_GE(slip_start.size(), 8u);
  // skip the start-up cycle; compare every later cycle with the analysis
  for (size_t n = 1; n + 1 < slip_start.size(); ++n) {
    const double period = slip_start[n + 1] - slip_start[n];
    EXPECT_NEAR(period, stick + slip, 0.005 * (stick + slip)) << "cycle " << n;
    // slip starts when the spring force reaches mu_s m g
    EXPECT_NEAR(k * x_at_slip_start[n], mu_s * m * g, 0.005 * mu_s * m * g) << "cycle " << n;
  }
  // during stick the mass moves with the belt: between a slip end and the
  // next slip start (inner 90 %), |v - vb| stays below the regularisation creep
  for (size_t n = 1; n + 1 < slip_start.size(); ++n) {
    double end = 0;
    for (const double e : slip_end)
      if (e < slip_start[n + 1] && e > slip_start[n]) end = e;
    ASSERT_GT(end, 0);
    EXPECT_NEAR(slip_start[n + 1] - end, stick, 0.01 * stick) << "stick duration, cycle " << n;
    for (size_t i = 0; i < t.size(); ++i) {
      const double margin = 0.05 * (slip_start[n + 1] - end);
      if (t[i] > end + margin && t[i] < slip_start[n + 1] - margin) {
        EXPECT_LT(std::abs(v[i] - vb), 1e-3) << "t = " << t[i];
      }
    }
  }
}

}  // namespace
}  // namespace mechflow
