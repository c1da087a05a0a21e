// Simulator guards: a crossing that keeps firing at one instant fails the run
// instead of looping; a run that fails before the solver is set up prints
// nothing from SUNDIALS; a step size at the resolution of time and a solver
// state that froze end the run with a message instead of rows.

#include <cmath>
#include <memory>
#include <vector>
#include <string>

#include <gtest/gtest.h>

#include "blocks/framework/diagram_builder.h"
#include "blocks/solver/simulator.h"
#include "mech/errors.h"

namespace mechflow::blocks {
namespace {

// x' = 1 from x = 0; crossing 0 fires when x rises through 1, and its handler
// puts x back `setback` below 1, so it fires again straight away: a modelling
// error (a "reset" that does not leave the switching surface).
class Stubborn : public Block {
 public:
  Stubborn(std::string name, double setback) : Block("stubborn", std::move(name)), setback_(setback) {
    DeclareOutputPort("x");
    DeclareNoFeedthrough();
    DeclareContinuousStates(1);
    DeclareZeroCrossing(CrossingDirection::kRising);
  }

 protected:
  void DoInitialize(const BlockContext& ctx) const override { ctx.state()[0] = 0.0; }
  void DoCalcOutput(int, const BlockContext& ctx) const override { ctx.output(0)[0] = ctx.state()[0]; }
  void DoCalcDerivatives(const BlockContext& ctx) const override { ctx.derivative()[0] = 1.0; }
  void DoCalcZeroCrossings(const BlockContext& ctx) const override {
    ctx.zero_crossings()[0] = ctx.state()[0] - 1.0;
  }
  void DoZeroCrossing(int, int, const BlockContext& ctx) const override { ctx.state()[0] = 1.0 - setback_; }

 private:
  double setback_;
};

SolverOptions Options() {
  SolverOptions options;
  options.t_end = 3.0;
  options.rtol = 1e-8;
  options.atol = 1e-10;
  options.output_interval = 0.1;
  return options;
}

TEST(SimulatorGuardsTest, ACrossingThatKeepsFiringFailsTheRun) {
  for (const double setback : {1e-13, 1e-11, 1e-10}) {
    DiagramBuilder builder;
    builder.AddBlock(std::make_unique<Stubborn>("stubborn", setback));
    auto diagram = builder.Build();
    Simulator sim(*diagram, Options(), {diagram->ResolveSignal("stubborn.x")});
    const RunOutcome outcome = sim.Run();
    ASSERT_FALSE(outcome.ok) << "setback " << setback;
    EXPECT_NE(outcome.failure.find("block 'stubborn' crossing 0 keeps firing at t = 1.0"), std::string::npos)
        << outcome.failure;
    EXPECT_NEAR(outcome.t_reached, 1.0, 1e-6);
    // the events handled and the rows before the failure are kept
    EXPECT_EQ(sim.stats().events, 100);
    ASSERT_EQ(sim.events().size(), 100u);
    EXPECT_NEAR(sim.events().back().time, 1.0, 1e-6);
    const Results& r = sim.results();
    ASSERT_GE(r.num_rows(), 10);
    EXPECT_NEAR(r.at(10, 0), 1.0, 1e-12);
    EXPECT_NEAR(r.at(10, 1), 1.0, 1e-6);
  }
}

TEST(SimulatorGuardsTest, EventsThatMoveOnAreNotStopped) {
  // the same block with a real setback fires every 0.25 s: 11 events in 3 s
  DiagramBuilder builder;
  builder.AddBlock(std::make_unique<Stubborn>("sawtooth", 0.25));
  auto diagram = builder.Build();
  Simulator sim(*diagram, Options(), {diagram->ResolveSignal("sawtooth.x")});
  const RunOutcome outcome = sim.Run();
  ASSERT_TRUE(outcome.ok) << outcome.failure;
  EXPECT_EQ(sim.stats().events, 8);  // 1.0, 1.25, ..., 2.75
}

// Fails the run at t_start, before the solver is set up: its modes cannot be
// made to agree. It declares a projection, so the projection's counters are
// asked for too.
class Unsettled : public Block {
 public:
  Unsettled() : Block("unsettled", "u") {
    DeclareOutputPort("x");
    DeclareNoFeedthrough();
    DeclareContinuousStates(1);
    DeclareProjection();
  }

 protected:
  void DoCalcOutput(int, const BlockContext& ctx) const override { ctx.output(0)[0] = ctx.state()[0]; }
  bool DoUpdateModes(const BlockContext&) const override {
    throw SimulationError("unsettled: no mode fits at the start");
  }
};

TEST(SimulatorGuardsTest, AFailureBeforeTheSolverIsSetUpPrintsNothing) {
  DiagramBuilder builder;
  builder.AddBlock(std::make_unique<Unsettled>());
  auto diagram = builder.Build();
  Simulator sim(*diagram, Options(), {diagram->ResolveSignal("u.x")});
  ::testing::internal::CaptureStderr();
  ::testing::internal::CaptureStdout();
  const RunOutcome outcome = sim.Run();
  const std::string out = ::testing::internal::GetCapturedStdout();
  const std::string err = ::testing::internal::GetCapturedStderr();
  ASSERT_FALSE(outcome.ok);
  EXPECT_EQ(outcome.failure, "unsettled: no mode fits at the start");
  EXPECT_EQ(outcome.t_reached, 0.0);
  EXPECT_EQ(err, "");  // no "[CVLS ERROR] ... Linear solver memory is NULL"
  EXPECT_EQ(out, "");
  EXPECT_EQ(sim.stats().steps, 0);
  EXPECT_EQ(sim.stats().jac_evals, 0);
  EXPECT_EQ(sim.stats().projections, 0);
}

// x' = 1 / (1 - t)^2: x = 1 / (1 - t) - 1 blows up at t = 1, and the step
// size with it.
class BlowUp : public Block {
 public:
  BlowUp() : Block("blow_up", "b") {
    DeclareOutputPort("x");
    DeclareNoFeedthrough();
    DeclareContinuousStates(1);
  }

 protected:
  void DoInitialize(const BlockContext& ctx) const override { ctx.state()[0] = 0.0; }
  void DoCalcOutput(int, const BlockContext& ctx) const override { ctx.output(0)[0] = ctx.state()[0]; }
  void DoCalcDerivatives(const BlockContext& ctx) const override {
    ctx.derivative()[0] = 1.0 / ((1.0 - ctx.time()) * (1.0 - ctx.time()));
  }
};

TEST(SimulatorGuardsTest, AStepAtTheResolutionOfTimeFailsWithAReason) {
  DiagramBuilder builder;
  builder.AddBlock(std::make_unique<BlowUp>());
  auto diagram = builder.Build();
  Simulator sim(*diagram, Options(), {diagram->ResolveSignal("b.x")});
  const RunOutcome outcome = sim.Run();
  ASSERT_FALSE(outcome.ok);
  EXPECT_NE(outcome.failure.find("the step size fell to the resolution of time"), std::string::npos)
      << outcome.failure;
  EXPECT_LT(outcome.t_reached, 1.0);
  EXPECT_GT(outcome.t_reached, 0.99);
}

TEST(SimulatorGuardsTest, FrozenMotionIsTheSameStateWithANonzeroSlope) {
  const std::vector<double> x = {1.5706729, 0.0}, moved = {1.5706730, 0.0};
  // a joint turning at 2.23 rad/s that stays put for 0.01 s: frozen
  EXPECT_EQ(FrozenState(x, x, std::vector<double>{2.23, 0.0}, 0.01, 1e-11, 1e-13), 0);
  // it moved, or nothing moves, or the change is below the tolerance
  EXPECT_EQ(FrozenState(x, moved, std::vector<double>{2.23, 0.0}, 0.01, 1e-11, 1e-13), -1);
  EXPECT_EQ(FrozenState(x, x, std::vector<double>{0.0, 0.0}, 0.01, 1e-11, 1e-13), -1);
  EXPECT_EQ(FrozenState(x, x, std::vector<double>{1e-20, 0.0}, 0.01, 1e-11, 1e-13), -1);
  EXPECT_EQ(FrozenState(x, x, std::vector<double>{0.0, -3.0}, 0.01, 1e-11, 1e-13), 1);
}

// y = (t, 1 / (t - 0.25)): its second element overflows at t = 0.25 alone
// (a row there: the interval is 0.125), as an interpolation between values
// near the largest double would.
class Overflow : public Block {
 public:
  Overflow() : Block("overflow", "tab") { DeclareOutputPort("y", 2); }

 protected:
  void DoCalcOutput(int, const BlockContext& ctx) const override {
    ctx.output(0)[0] = ctx.time();
    ctx.output(0)[1] = 1.0 / (ctx.time() - 0.25);
  }
};

// y = 2 u.
class Twice : public Block {
 public:
  explicit Twice(std::string name) : Block("twice", std::move(name)) {
    DeclareInputPort("u", 2);
    DeclareOutputPort("y", 2);
  }

 protected:
  void DoCalcOutput(int, const BlockContext& ctx) const override {
    for (int i = 0; i < 2; ++i) ctx.output(0)[i] = 2.0 * ctx.input(0)[i];
  }
};

TEST(SimulatorGuardsTest, AnOutputThatIsNotFiniteFailsTheRunNamingBlockAndPort) {
  // the downstream block first, so its signal comes first in the layout too:
  // the message names the cause, in schedule order
  DiagramBuilder builder;
  builder.AddBlock(std::make_unique<Twice>("twice"), "d.xml:3");
  builder.AddBlock(std::make_unique<Overflow>(), "d.xml:2");
  builder.Connect("tab.y", "twice.u");
  auto diagram = builder.Build();
  SolverOptions options = Options();
  options.output_interval = 0.125;
  Simulator sim(*diagram, options, {diagram->ResolveSignal("twice.y")});
  const RunOutcome outcome = sim.Run();
  ASSERT_FALSE(outcome.ok);
  EXPECT_EQ(outcome.failure,
            "block 'tab' (d.xml:2) output 'y[1]' is not finite (inf) at t = 0.25; the rows before are kept (a value "
            "out of the range of double precision, or undefined: check what the block computes from its inputs and "
            "parameters there)");
  EXPECT_EQ(outcome.t_reached, 0.25);
  // the rows before, and not the one with inf
  const Results& r = sim.results();
  ASSERT_EQ(r.num_rows(), 2);
  EXPECT_EQ(r.at(1, 0), 0.125);
  EXPECT_EQ(r.at(1, 2), 2.0 / (0.125 - 0.25));
}

// x' = -x; its output y reads x, but is NaN whenever it is computed for a
// right-hand side (a Newton iterate that strays); `sink` integrates
// nothing from it (s' = 0), so y sits in the dynamics schedule.
class Stray : public Block {
 public:
  Stray() : Block("stray", "stray") {
    DeclareOutputPort("y");
    DeclareNoFeedthrough();
    DeclareContinuousStates(1);
  }

 protected:
  void DoInitialize(const BlockContext& ctx) const override { ctx.state()[0] = 1.0; }
  void DoCalcOutput(int, const BlockContext& ctx) const override {
    ctx.output(0)[0] = ctx.derivatives_follow() ? std::nan("") : ctx.state()[0];
  }
  void DoCalcDerivatives(const BlockContext& ctx) const override { ctx.derivative()[0] = -ctx.state()[0]; }
};

class Sink : public Block {
 public:
  Sink() : Block("sink", "sink") {
    DeclareInputPort("u");
    DeclareOutputPort("s");
    DeclareNoFeedthrough();
    DeclareContinuousStates(1);
  }

 protected:
  void DoInitialize(const BlockContext& ctx) const override { ctx.state()[0] = 0.0; }
  void DoCalcOutput(int, const BlockContext& ctx) const override { ctx.output(0)[0] = ctx.state()[0]; }
  void DoCalcDerivatives(const BlockContext& ctx) const override {
    ctx.derivative()[0] = std::isnan(ctx.input(0)[0]) ? 0.0 : 0.0;
  }
};

TEST(SimulatorGuardsTest, ValuesThatStrayOnlyInsideTheSolverDoNotFailTheRun) {
  DiagramBuilder builder;
  builder.AddBlock(std::make_unique<Stray>());
  builder.AddBlock(std::make_unique<Sink>());
  builder.Connect("stray.y", "sink.u");
  auto diagram = builder.Build();
  Simulator sim(*diagram, Options(), {diagram->ResolveSignal("stray.y")});
  const RunOutcome outcome = sim.Run();
  ASSERT_TRUE(outcome.ok) << outcome.failure;
  const Results& r = sim.results();
  ASSERT_EQ(r.num_rows(), 31);
  EXPECT_NEAR(r.at(30, 1), std::exp(-3.0), 1e-7);
}

// x' = 0, then NaN from t = 0.5 on: the failure names the state.
class NanRate : public Block {
 public:
  NanRate() : Block("nan_rate", "bad") {
    DeclareOutputPort("x");
    DeclareNoFeedthrough();
    DeclareContinuousStates(1);
  }

 protected:
  void DoInitialize(const BlockContext& ctx) const override { ctx.state()[0] = 0.0; }
  void DoCalcOutput(int, const BlockContext& ctx) const override { ctx.output(0)[0] = ctx.state()[0]; }
  void DoCalcDerivatives(const BlockContext& ctx) const override {
    ctx.derivative()[0] = ctx.time() < 0.5 ? 1.0 : std::nan("");
  }
};

TEST(SimulatorGuardsTest, ADerivativeThatIsNotFiniteNamesItsBlockAndState) {
  DiagramBuilder builder;
  builder.AddBlock(std::make_unique<NanRate>(), "d.xml:4");
  auto diagram = builder.Build();
  Simulator sim(*diagram, Options(), {diagram->ResolveSignal("bad.x")});
  const RunOutcome outcome = sim.Run();
  ASSERT_FALSE(outcome.ok);
  EXPECT_NE(outcome.failure.find("the derivative of block 'bad' (d.xml:4) state '" + diagram->block(0).state_name(0) +
                                 "' is not finite (nan) at t = 0.5"),
            std::string::npos)
      << outcome.failure;
  EXPECT_GE(outcome.t_reached, 0.4);  // the last row, or the last step before 0.5
  EXPECT_LE(outcome.t_reached, 0.5);
}

}  // namespace
}  // namespace mechflow::blocks
