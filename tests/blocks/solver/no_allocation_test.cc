// The evaluation passes allocate nothing (house style, architecture rule 4).
//
// Every example diagram is loaded and set up the way blocks::Simulator sets up
// its Context; then the passes the solver callbacks run (outputs, derivatives,
// zero crossings) are called 1000 times with malloc counted. Expected:
// zero calls. Lua allocates through LuaState's own allocator, so for
// diagrams with Lua blocks the Lua heap is checked too, with Lua's garbage collector stopped so that garbage collected
// during the loop cannot hide an allocation made in it.
//
// Not covered: malloc called directly (CVODE's own allocations happen at
// set-up, outside the right-hand side), and the event/reinitialisation path.

#include <algorithm>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <lua.hpp>

#include "blocks/framework/evaluation.h"
#include "diagrams/loader.h"
#include "scripting/lua_state.h"
#include "tests/blocks/block_test_util.h"
#include "tests/malloc_counter.h"

// ---------------------------------------------------------------------------

namespace mechflow {
namespace {

// Counts allocations while alive. No GoogleTest macro may run inside
// (a failing assertion allocates its message).
class CountAllocations {
 public:
  CountAllocations() {
    g_calls = 0;
    g_counting = true;
  }
  ~CountAllocations() { g_counting = false; }
  long calls() const { return g_calls.load(); }
};

// The counter itself works: an allocation in the counted region is seen.
// (::operator new is called directly because a new-expression may be elided.)
TEST(NoAllocationTest, CounterSeesAnAllocation) {
  long calls = 0;
  {
    CountAllocations counter;
    void* p = ::operator new(64);
    ::operator delete(p);
    calls = counter.calls();
  }
  EXPECT_EQ(calls, 1);
}

class ExampleDiagram : public ::testing::TestWithParam<const char*> {};

TEST_P(ExampleDiagram, EvaluationPassesDoNotAllocate) {
  const std::string path = std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/" + GetParam();
  const diagrams::LoadedDiagram loaded = diagrams::LoadDiagram(path);
  const blocks::Diagram& d = *loaded.diagram;

  // the Context as blocks::Simulator sizes it; x, xdot and crossings stand in
  // for the SUNDIALS vectors
  blocks::Context ctx;
  ctx.signals.assign(d.num_signals(), 0.0);
  ctx.discrete.assign(d.num_discrete_states(), 0.0);
  std::vector<double> x(std::max(1, d.num_states()), 0.0);
  std::vector<double> xdot(x.size(), 0.0);
  std::vector<double> crossings(std::max(1, d.num_zero_crossings()), 0.0);
  ctx.x = x.data();
  ctx.xdot = xdot.data();
  ctx.crossings = crossings.data();
  const double t0 = loaded.solver.t_start, t_end = loaded.solver.t_end;
  ctx.time = t0;
  blocks::InitializeStates(d, &ctx);
  ASSERT_TRUE(blocks::SettleModes(d, &ctx));  // as the simulator does before integrating

  // Lua: collect what loading left behind, then stop the collector so any
  // allocation in the loop shows as growth
  lua_State* L = loaded.lua->get();
  lua_gc(L, LUA_GCCOLLECT);
  lua_gc(L, LUA_GCSTOP);
  // One evaluation before counting: Lua grows its list of call frames the
  // first time a call goes one level deeper (and a full collection shrinks
  // it again), once per depth, not per call.
  ++ctx.evaluation;
  blocks::EvaluateOutputs(d, &ctx);
  blocks::EvaluateDerivatives(d, &ctx);
  blocks::EvaluateZeroCrossings(d, &ctx);
  const std::size_t lua_before = loaded.lua->memory_in_use();

  constexpr int kCalls = 1000;
  long new_calls = 0;
  {
    CountAllocations counter;
    for (int i = 0; i < kCalls; ++i) {
      ctx.time = t0 + (t_end - t0) * i / kCalls;
      ++ctx.evaluation;
      blocks::EvaluateOutputs(d, &ctx);
      blocks::EvaluateDerivatives(d, &ctx);
      blocks::EvaluateZeroCrossings(d, &ctx);
    }
    new_calls = counter.calls();
  }
  const std::size_t lua_after = loaded.lua->memory_in_use();
  lua_gc(L, LUA_GCRESTART);

  EXPECT_EQ(new_calls, 0) << "allocation in " << kCalls << " evaluations of " << GetParam();
  EXPECT_EQ(lua_after, lua_before) << "Lua heap changed by " << static_cast<long>(lua_after) - static_cast<long>(lua_before)
                                   << " bytes in " << kCalls << " evaluations of " << GetParam();
}

// Every block of the standard library in one diagram, driven by time-varying
// signals so that modes switch during the loop: the evaluation passes and the
// mode updates allocate nothing.
TEST(NoAllocationTest, StandardLibraryBlocks) {
  using blocks::testing::MakeBlock;
  blocks::DiagramBuilder builder;
  const std::vector<std::pair<std::string, blocks::testing::ParamTexts>> blocks_made = {
      {"clock", {}}, {"sine", {}}, {"step", {{"time", "0.3"}}}, {"ramp", {{"start", "0.2"}}},
      {"constant", {{"value", "2"}}}, {"table", {{"points", "0 0; 0.5 1; 1 -1"}}}, {"gain", {{"k", "3"}}},
      {"sum", {{"signs", "+-+"}}}, {"product", {{"operations", "**/"}}}, {"abs", {}},
      {"saturation", {{"lower", "-0.5"}, {"upper", "0.5"}}}, {"dead_zone", {{"start", "-0.2"}, {"end", "0.2"}}},
      {"integrator", {{"upper", "0.3"}, {"lower", "-0.3"}, {"reset", "either"}}},
      {"first_order_lag", {{"time_constant", "0.1"}}},
      {"friction_from_normal_force", {{"mu_static", "0.5"}, {"mu_dynamic", "0.3"}}},
      {"sample_hold", {{"period", "0.1"}}}, {"recorder", {{"inputs", "2"}}},
      {"lookup", {{"points", "-1 0; 0 1; 1 0"}}},
      {"lookup_2d", {{"x", "-1 0 1"}, {"y", "-1 1"}, {"values", "0 1; 1 2; 2 0"}, {"interpolation", "cubic"}}},
      {"motion_sine", {}}, {"motion_table", {{"points", "0 0; 1 1; 1.5 0; 2 2"}}},
      {"motion_filter", {{"frequency", "5"}}}};
  for (const auto& [type, params] : blocks_made) builder.AddBlock(MakeBlock(type, type, params));
  const std::vector<std::pair<const char*, const char*>> connections = {
      {"sine", "gain"}, {"sine", "sum.u1"}, {"table", "sum.u2"}, {"ramp", "sum.u3"}, {"sine", "product.u1"},
      {"step", "product.u2"}, {"constant", "product.u3"}, {"sine", "abs"}, {"gain", "saturation"},
      {"sine", "dead_zone"}, {"sum", "integrator.u"}, {"sine", "integrator.reset"}, {"table", "integrator.x0"},
      {"sine", "first_order_lag"}, {"constant", "friction_from_normal_force.N"},
      {"sine", "friction_from_normal_force.v"}, {"clock", "sample_hold"}, {"integrator", "recorder.u1"},
      {"saturation", "recorder.u2"}, {"sine", "lookup"}, {"sine", "lookup_2d.u1"}, {"table", "lookup_2d.u2"},
      {"sine", "motion_filter"}};
  for (const auto& [from, to] : connections) builder.Connect(from, to);
  const auto diagram = builder.Build();
  const blocks::Diagram& d = *diagram;

  blocks::Context ctx;
  ctx.signals.assign(d.num_signals(), 0.0);
  ctx.discrete.assign(d.num_discrete_states(), 0.0);
  std::vector<double> x(std::max(1, d.num_states()), 0.0);
  std::vector<double> xdot(x.size(), 0.0);
  std::vector<double> crossings(std::max(1, d.num_zero_crossings()), 0.0);
  ctx.x = x.data();
  ctx.xdot = xdot.data();
  ctx.crossings = crossings.data();
  ctx.time = 0.0;
  blocks::InitializeStates(d, &ctx);
  ASSERT_TRUE(blocks::SettleModes(d, &ctx));

  constexpr int kCalls = 1000;
  long new_calls = 0;
  bool settled = true;
  {
    CountAllocations counter;
    for (int i = 0; i < kCalls; ++i) {
      ctx.time = 2.0 * i / kCalls;
      ++ctx.evaluation;
      blocks::EvaluateOutputs(d, &ctx);
      blocks::EvaluateDerivatives(d, &ctx);
      blocks::EvaluateZeroCrossings(d, &ctx);
      // as after an event: modes follow the inputs (and the reset may fire)
      settled &= blocks::SettleModes(d, &ctx);
    }
    new_calls = counter.calls();
  }
  EXPECT_TRUE(settled);
  EXPECT_EQ(new_calls, 0) << "allocation in " << kCalls << " evaluations of the standard blocks";
}

INSTANTIATE_TEST_SUITE_P(Examples, ExampleDiagram,
                         ::testing::Values("damped_oscillator_blocks.xml", "stick_slip_blocks.xml",
                                           "van_der_pol_stiff.xml", "bouncing_ball_blocks.xml",
                                           "leaf_spring.xml", "elast_friction.xml", "slider_crank.xml",
                                           "falling.xml", "rollers.xml", "tension_mechanism.xml",
                                           "cart_pendulum_friction.xml", "quarter_car.xml"),
                         [](const ::testing::TestParamInfo<const char*>& info) {
                           std::string name = info.param;
                           name = name.substr(0, name.find('.'));
                           return name;
                         });

}  // namespace
}  // namespace mechflow
