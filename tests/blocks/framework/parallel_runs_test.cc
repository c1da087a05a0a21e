// One built diagram run by several Simulators at once, one per thread: every
// run's scratch (a mechanism's workspace, an algebraic loop's Newton arrays, a
// lookup's buffers, the friction block's largest pull) lives in its own
// Context, so each result is the sequential run's, bit for bit.

#include <cstring>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "blocks/framework/evaluation.h"
#include "blocks/library/friction_from_normal_force.h"
#include "blocks/library/mechanism_block.h"
#include "blocks/solver/simulator.h"
#include "tests/test_util.h"

namespace mechflow {
namespace {

// No Lua at run time (a diagram's Lua state is one per load: see
// scripting/lua_state.h). A four-bar (a closed loop, projected after every
// step) whose pin reaction presses a friction block that feeds its own normal
// force back (an algebraic loop through friction_from_normal_force); a lookup
// with corners (events) and a cubic 2-D table read the crank.
const char* const kDiagram = R"(<diagram name="parallel">
  <mechanism name="m" gravity="0 0 -9.81">
    <body name="Crank" mass="0.3" com="0 0.15 0" inertia="0.00225 1e-5 0.00225"/>
    <body name="Coupler" mass="0.8" com="0 0.4 0" inertia="0.0427 1e-5 0.0427"/>
    <body name="Rocker" mass="0.6" com="0 0.3 0" inertia="0.018 1e-5 0.018"/>
    <joint name="j1" type="rotational" body1="Base0" body2="Crank" axis="1 0 0" q0="1.2" v0="6"/>
    <joint name="j2" type="rotational" body1="Crank" body2="Coupler" point1="0 0.3 0" axis="1 0 0" q0="-1"/>
    <joint name="j3" type="rotational" body1="Base0" body2="Rocker" point1="0 0.7 0" axis="1 0 0" q0="1.9"/>
    <joint name="j4" type="rotational" body1="Coupler" body2="Rocker" point1="0 0.8 0" point2="0 0.6 0" axis="1 0 0"/>
    <sensor name="crank" kind="coordinate" dof="j1"/>
    <sensor name="rate" kind="velocity" dof="j1"/>
    <sensor name="N" kind="reaction_force" joint="j4" component="z"/>
  </mechanism>
  <blocks>
    <block type="lookup" name="table" points="0 0; 2 1; 4 3; 8 2"/>
    <block type="lookup_2d" name="map" x="-10 0 10 20" y="-3 0 1 3"
           values="1 2 3 4; 2 3 5 4; 3 4 6 5; 1 2 2 3" interpolation="cubic"/>
    <block type="friction_from_normal_force" name="coulomb" mu_static="0.4" mu_dynamic="0.3"/>
    <block type="gain" name="k" k="0.5"/>
    <block type="sum" name="s"/>
  </blocks>
  <connections>
    <connect from="m.crank" to="table.u"/>
    <connect from="m.crank" to="map.u1"/>
    <connect from="coulomb.F" to="map.u2"/>
    <connect from="m.N" to="s.u1"/>
    <connect from="k.y" to="s.u2"/>
    <connect from="s.y" to="coulomb.N"/>
    <connect from="m.rate" to="coulomb.v"/>
    <connect from="coulomb.F" to="k.u"/>
  </connections>
  <solver t_end="1" rtol="1e-8" atol="1e-10"/>
  <output interval="0.01">
    <log signal="m.crank"/>
    <log signal="m.N"/>
    <log signal="coulomb.F"/>
    <log signal="table.y"/>
    <log signal="map.y"/>
  </output>
</diagram>)";

// What a run gives: every logged value and the figures read after it.
struct RunResult {
  bool ok = false;
  std::string failure;
  std::vector<std::vector<double>> columns;
  blocks::LoopStats loop;
  double worst_residual = -1.0;
  std::string pulling;
  long events = 0;
};

RunResult RunOnce(const diagrams::LoadedDiagram& loaded) {
  const blocks::Diagram& d = *loaded.diagram;
  blocks::Simulator sim(d, loaded.solver, loaded.logged);
  const blocks::RunOutcome outcome = sim.Run();
  RunResult r;
  r.ok = outcome.ok;
  r.failure = outcome.failure;
  r.events = sim.stats().events;
  for (int c = 0; c < sim.results().num_columns(); ++c) r.columns.push_back(sim.results().Column(c));
  r.loop = d.loops().at(0).stats(sim.context());
  const int m = d.FindBlock("m"), f = d.FindBlock("coulomb");
  const auto& mechanism = dynamic_cast<const blocks::MechanismBlock&>(d.block(m));
  r.worst_residual = mechanism.worst_constraint_residual(sim.context(), m);
  r.pulling = dynamic_cast<const blocks::FrictionFromNormalForceBlock&>(d.block(f)).PullingWarning(sim.context(), f);
  return r;
}

// Equal bit for bit (memcmp, so -0.0 and NaN payloads count too).
bool SameBits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

void ExpectSameRun(const RunResult& run, const RunResult& reference, const char* which) {
  ASSERT_TRUE(run.ok) << which << ": " << run.failure;
  ASSERT_EQ(run.columns.size(), reference.columns.size()) << which;
  for (std::size_t c = 0; c < run.columns.size(); ++c)
    EXPECT_TRUE(SameBits(run.columns[c], reference.columns[c])) << which << ": column " << c << " differs";
  EXPECT_EQ(run.loop.solves, reference.loop.solves) << which;
  EXPECT_EQ(run.loop.iterations, reference.loop.iterations) << which;
  EXPECT_EQ(run.loop.jacobians, reference.loop.jacobians) << which;
  EXPECT_EQ(run.worst_residual, reference.worst_residual) << which;
  EXPECT_EQ(run.pulling, reference.pulling) << which;
  EXPECT_EQ(run.events, reference.events) << which;
}

TEST(ParallelRunsTest, OneDiagramOnTwoThreadsGivesTheSequentialRunBitForBit) {
  const diagrams::LoadedDiagram loaded = testing::LoadXml(kDiagram);
  const blocks::Diagram& d = *loaded.diagram;
  ASSERT_EQ(d.loops().size(), 1u);
  ASSERT_TRUE(d.block(d.FindBlock("m")).has_projection());

  const RunResult reference = RunOnce(loaded);
  ASSERT_TRUE(reference.ok) << reference.failure;
  ASSERT_GT(reference.columns.at(0).size(), 50u);
  EXPECT_GT(reference.events, 0) << "the lookup's corners were never crossed";
  EXPECT_GT(reference.loop.solves, 0);
  EXPECT_GT(reference.worst_residual, 0.0) << "projection never ran";

  RunResult a, b;
  std::thread first([&] { a = RunOnce(loaded); });
  std::thread second([&] { b = RunOnce(loaded); });
  first.join();
  second.join();
  ExpectSameRun(a, reference, "first thread");
  ExpectSameRun(b, reference, "second thread");
  // and again on this thread: nothing a run leaves behind changes the next
  ExpectSameRun(RunOnce(loaded), reference, "a later run");
}

// Each Context has its own scratch: a run's figures are its own, not those
// of another run of the same diagram that went on meanwhile.
TEST(ParallelRunsTest, FiguresAreTheRunsOwn) {
  const diagrams::LoadedDiagram loaded = testing::LoadXml(kDiagram);
  const blocks::Diagram& d = *loaded.diagram;
  blocks::Simulator one(d, loaded.solver, loaded.logged);
  blocks::SolverOptions shorter = loaded.solver;
  shorter.t_end = 0.1;
  blocks::Simulator two(d, shorter, loaded.logged);
  ASSERT_TRUE(one.Run().ok);
  ASSERT_TRUE(two.Run().ok);
  EXPECT_GT(d.loops()[0].stats(one.context()).solves, d.loops()[0].stats(two.context()).solves);
  // a Context no run prepared has no scratch: the figures are those of no run
  const blocks::Context unprepared;
  EXPECT_EQ(d.loops()[0].stats(unprepared).solves, 0);
}

// A diagram with Lua at run time has one Lua state: a run on another thread
// while a run holds it is refused, with what to do; once that run's Context
// is gone, another thread may run it.
TEST(ParallelRunsTest, ALuaDiagramRunsOnOneThreadAtATime) {
  const diagrams::LoadedDiagram loaded = testing::LoadXml(R"(<diagram name="lua">
  <blocks>
    <block type="clock" name="clk"/>
    <block type="expression" name="e" expr="2 * u" inputs="u"/>
  </blocks>
  <connections><connect from="clk.y" to="e.u"/></connections>
  <solver t_end="0.1"/>
  <output interval="0.05"><log signal="e.y"/></output>
</diagram>)");
  ASSERT_TRUE(loaded.diagram->run_claim());
  auto holder = std::make_unique<blocks::Simulator>(*loaded.diagram, loaded.solver, loaded.logged);
  ASSERT_TRUE(holder->Run().ok);
  blocks::RunOutcome refused, later;
  std::thread([&] { refused = blocks::Simulator(*loaded.diagram, loaded.solver, loaded.logged).Run(); }).join();
  EXPECT_FALSE(refused.ok);
  EXPECT_NE(refused.failure.find("in use by a run on another thread"), std::string::npos) << refused.failure;
  EXPECT_NE(refused.failure.find("load the diagram once per thread"), std::string::npos) << refused.failure;
  // on the holder's own thread runs may overlap (an analysis next to a run)
  EXPECT_TRUE(blocks::Simulator(*loaded.diagram, loaded.solver, loaded.logged).Run().ok);
  holder.reset();
  std::thread([&] { later = blocks::Simulator(*loaded.diagram, loaded.solver, loaded.logged).Run(); }).join();
  EXPECT_TRUE(later.ok) << later.failure;
}

// Without Lua at run time a diagram claims nothing.
TEST(ParallelRunsTest, ADiagramWithoutLuaClaimsNothing) {
  EXPECT_FALSE(testing::LoadXml(kDiagram).diagram->run_claim());
}

}  // namespace
}  // namespace mechflow
