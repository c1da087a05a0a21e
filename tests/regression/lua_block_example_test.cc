// diagrams/examples/damped_oscillator_lua.xml: the damped oscillator as one
// Lua block, against the underdamped closed form and against the same system
// built from integrators and gains (damped_oscillator_blocks.xml).

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "blocks/simulator.h"
#include "diagrams/loader.h"

namespace mechflow {
namespace {

const double kPi = 3.14159265358979323846;

struct ExampleRun {
  diagrams::LoadedDiagram loaded;
  std::unique_ptr<blocks::Simulator> sim;
  blocks::RunOutcome outcome;

  explicit ExampleRun(const std::string& name)
      : loaded(diagrams::LoadDiagram(std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/" + name)) {
    sim = std::make_unique<blocks::Simulator>(*loaded.diagram, loaded.solver, loaded.logged);
    outcome = sim->Run();
  }
  std::vector<double> Column(const std::string& name) const {
    const int c = sim->results().FindColumn(name);
    EXPECT_GE(c, 0) << "no column " << name;
    return c < 0 ? std::vector<double>() : sim->results().Column(c);
  }
};

TEST(LuaBlockExampleTest, DampedOscillatorMatchesClosedForm) {
  ExampleRun run("damped_oscillator_lua.xml");
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const double m = 1000, f = 1, beta = 0.1, x0 = 0.5;
  const double c = 4 * kPi * kPi * f * f * m, d = 2 * beta * std::sqrt(m * c);
  const double w = std::sqrt(c / m), zeta = d / (2 * std::sqrt(m * c)), wd = w * std::sqrt(1 - zeta * zeta);
  const auto t = run.Column("time"), x = run.Column("x");
  ASSERT_EQ(t.size(), 1001u);
  EXPECT_DOUBLE_EQ(t.back(), 10.0);
  double max_error = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double exact =
        std::exp(-zeta * w * t[i]) * (x0 * std::cos(wd * t[i]) + zeta * w * x0 / wd * std::sin(wd * t[i]));
    max_error = std::max(max_error, std::abs(x[i] - exact));
  }
  // the bound of the blocks version at rtol 1e-8 (tests/regression/examples_test.cc)
  EXPECT_LT(max_error, 1e-5);
}

// The Lua code computes (-c/m) x + (-d/m) v in the order the gains and the
// sum do, so the solver sees the same numbers and takes the same steps: the
// two runs agree to rounding, far inside the solver tolerance (atol 1e-10).
TEST(LuaBlockExampleTest, DampedOscillatorMatchesBlocksVersion) {
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

}  // namespace
}  // namespace mechflow
