// Simulator tests on tiny hand-built diagrams with closed-form answers.

#include "blocks/solver/simulator.h"

#include <cmath>

#include <gtest/gtest.h>

#include "blocks/framework/diagram_builder.h"

namespace mechflow::blocks {
namespace {

// x' = a * x (test-local block: one state, output y = x, no inputs).
class Exponential : public Block {
 public:
  Exponential(std::string name, double a, double x0) : Block("exponential", name), a_(a), x0_(x0) {
    DeclareOutputPort("y");
    DeclareContinuousStates(1);
  }

 protected:
  void DoInitialize(const BlockContext& ctx) const override { ctx.state()[0] = x0_; }
  void DoCalcOutput(int, const BlockContext& ctx) const override { ctx.output(0)[0] = ctx.state()[0]; }
  void DoCalcDerivatives(const BlockContext& ctx) const override {
    ctx.derivative()[0] = a_ * ctx.state()[0];
  }

 private:
  double a_, x0_;
};

TEST(SimulatorTest, ExponentialDecayMatchesClosedForm) {
  DiagramBuilder builder;
  builder.AddBlock(std::make_unique<Exponential>("e", -2.0, 1.0));
  auto diagram = builder.Build();
  SolverOptions options;
  options.t_end = 2.0;
  options.rtol = 1e-10;
  options.atol = 1e-12;
  options.output_interval = 0.1;
  Simulator sim(*diagram, options, {diagram->ResolveSignal("e.y")});
  const RunOutcome outcome = sim.Run();
  ASSERT_TRUE(outcome.ok) << outcome.failure;
  const Results& r = sim.results();
  ASSERT_EQ(r.num_rows(), 21);
  for (int i = 0; i < r.num_rows(); ++i) {
    EXPECT_NEAR(r.at(i, 0), 0.1 * i, 1e-12);
    EXPECT_NEAR(r.at(i, 1), std::exp(-2.0 * r.at(i, 0)), 1e-8);
  }
  EXPECT_GT(sim.stats().steps, 0);
}

}  // namespace
}  // namespace mechflow::blocks
