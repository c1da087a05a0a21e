// The "expression" block, built through its registry entry, wired with
// DiagramBuilder and run by blocks::Simulator.

#include "scripting/expression_block.h"

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "blocks/framework/diagram_builder.h"
#include "blocks/solver/simulator.h"
#include "mech/errors.h"
#include "scripting/identifiers.h"
#include "scripting/lua_state.h"
#include "tests/test_util.h"

namespace mechflow::scripting {
namespace {

using mechflow::testing::InputErrorOf;
using ::testing::HasSubstr;
using ::testing::StartsWith;

// y = x, x' = u, x(0) = initial: a test-local integrator, so these tests do
// not depend on the block library.
class TestIntegrator : public blocks::Block {
 public:
  TestIntegrator(std::string name, double initial) : Block("test_integrator", std::move(name)), initial_(initial) {
    DeclareInputPort("u");
    DeclareOutputPort("y");
    DeclareContinuousStates(1);
    DeclareNoFeedthrough();
  }

 protected:
  void DoInitialize(const blocks::BlockContext& ctx) const override { ctx.state()[0] = initial_; }
  void DoCalcOutput(int, const blocks::BlockContext& ctx) const override { ctx.output(0)[0] = ctx.state()[0]; }
  void DoCalcDerivatives(const blocks::BlockContext& ctx) const override {
    ctx.derivative()[0] = ctx.input_scalar(0);
  }

 private:
  double initial_;
};

class ExpressionBlockTest : public ::testing::Test {
 protected:
  ExpressionBlockTest() {
    ids_.Add("A", "3", "f.xml:1");
    ids_.Add("k", "2", "f.xml:2");
    ids_.Evaluate(lua_);
    RegisterScriptingBlocks(&registry_, &lua_, &ids_);
  }

  // An expression block made by the registry, as the loader makes it.
  std::unique_ptr<blocks::Block> Make(const std::string& name, const std::string& expr, const std::string* inputs) {
    blocks::BlockParams params;
    params.SetText("expr", expr);
    if (inputs) params.SetText("inputs", *inputs);
    return registry_.Find("expression")->create(name, params);
  }

  // Runs expression block `f` feeding integrator `x` (and, with `feedback`,
  // x back into f's input "x") and returns the outcome; x.y is logged.
  blocks::RunOutcome Run(const std::string& expr, bool feedback, double t_end, std::vector<double>* t,
                         std::vector<double>* x) {
    const std::string inputs = feedback ? "x" : "";
    blocks::DiagramBuilder builder;
    builder.AddBlock(Make("f", expr, &inputs));
    builder.AddBlock(std::make_unique<TestIntegrator>("x", feedback ? 1.0 : 0.0));
    builder.Connect("f.y", "x.u");
    if (feedback) builder.Connect("x.y", "f.x");
    diagram_ = builder.Build();
    blocks::SolverOptions options;
    options.t_end = t_end;
    options.rtol = 1e-10;
    options.atol = 1e-12;
    options.output_interval = 0.1;
    blocks::Simulator sim(*diagram_, options, {diagram_->ResolveSignal("x.y")});
    const blocks::RunOutcome outcome = sim.Run();
    *t = sim.results().Column(0);
    *x = sim.results().Column(sim.results().FindColumn("x.y"));
    return outcome;
  }

  // declared first: blocks hold compiled Lua functions, so Lua goes last
  LuaState lua_;
  IdentifierTable ids_;
  blocks::BlockRegistry registry_;
  std::unique_ptr<blocks::Diagram> diagram_;
};

TEST_F(ExpressionBlockTest, RegistryDescribesTheParameters) {
  const blocks::BlockType* type = registry_.Find("expression");
  ASSERT_NE(type, nullptr);
  const blocks::ParamSpec* expr = type->FindParam("expr");
  ASSERT_NE(expr, nullptr);
  EXPECT_EQ(expr->kind, blocks::ParamKind::kText);
  EXPECT_TRUE(expr->required);
  const blocks::ParamSpec* inputs = type->FindParam("inputs");
  ASSERT_NE(inputs, nullptr);
  EXPECT_EQ(inputs->kind, blocks::ParamKind::kText);
  EXPECT_FALSE(inputs->required);
  EXPECT_EQ(inputs->default_value, "u");
}

TEST_F(ExpressionBlockTest, OneScalarInputPerNameAllFeedingY) {
  const std::string two = "y1  y2", none = " ";
  const auto b = Make("f", "k * (1 - y1^2) * y2 - y1 + A", &two);
  EXPECT_EQ(b->type(), "expression");
  EXPECT_EQ(b->name(), "f");
  ASSERT_EQ(b->num_inputs(), 2);
  EXPECT_EQ(b->input_port(0).name, "y1");
  EXPECT_EQ(b->input_port(1).name, "y2");
  EXPECT_EQ(b->input_port(1).width, 1);
  ASSERT_EQ(b->num_outputs(), 1);
  EXPECT_EQ(b->output_port(0).name, "y");
  EXPECT_EQ(b->output_port(0).width, 1);
  EXPECT_TRUE(b->HasFeedthrough(0, 0));
  EXPECT_TRUE(b->HasFeedthrough(1, 0));
  EXPECT_EQ(b->num_states(), 0);
  EXPECT_EQ(Make("g", "sin(t)", &none)->num_inputs(), 0);
  const auto default_inputs = Make("h", "2*u", nullptr);
  ASSERT_EQ(default_inputs->num_inputs(), 1);
  EXPECT_EQ(default_inputs->input_port(0).name, "u");
}

TEST_F(ExpressionBlockTest, BadInputNamesAndExpressionsAreInputErrors) {
  auto error = [&](const std::string& expr, const std::string& inputs) {
    return InputErrorOf([&] { Make("f", expr, &inputs); });
  };
  EXPECT_EQ(error("t", "t"), "input name 't' must be a Lua name (letters, digits, '_'; not a keyword) other than t");
  EXPECT_THAT(error("u", "end"), StartsWith("input name 'end' must be a Lua name"));
  EXPECT_THAT(error("u", "u.1"), StartsWith("input name 'u.1' must be a Lua name"));
  EXPECT_EQ(error("u", "u u"), "input name 'u' is given twice");
  EXPECT_EQ(error("K", "K"), "input name 'K' is also the name of the identifier 'k' (f.xml:2); rename the input");
  EXPECT_EQ(error("u +* 2", "u"), "expression 'u +* 2' does not compile: block 'f':1: unexpected symbol near '*'");
  EXPECT_EQ(error("w", "u"), "expression 'w' uses the unknown name 'w'; its arguments are t, u");
}

TEST_F(ExpressionBlockTest, IntegratedSineMatchesClosedForm) {
  std::vector<double> t, x;
  const blocks::RunOutcome outcome = Run("a*sin(t)", /*feedback=*/false, 5.0, &t, &x);
  ASSERT_TRUE(outcome.ok) << outcome.failure;
  ASSERT_EQ(t.size(), 51u);
  // x = 3 (1 - cos t); BDF's global error at rtol 1e-10 stays well below 1e-6
  for (std::size_t i = 0; i < t.size(); ++i) EXPECT_NEAR(x[i], 3 * (1 - std::cos(t[i])), 1e-6) << t[i];
}

TEST_F(ExpressionBlockTest, InputsFeedTheExpression) {
  std::vector<double> t, x;
  const blocks::RunOutcome outcome = Run("-K*x", /*feedback=*/true, 2.0, &t, &x);
  ASSERT_TRUE(outcome.ok) << outcome.failure;
  // x' = -2 x, x(0) = 1: x = exp(-2 t)
  for (std::size_t i = 0; i < t.size(); ++i) EXPECT_NEAR(x[i], std::exp(-2 * t[i]), 1e-7) << t[i];
}

TEST_F(ExpressionBlockTest, LuaErrorFailsTheRunAtItsTime) {
  std::vector<double> t, x;
  const blocks::RunOutcome outcome = Run("t < 0.5 and 1 or error('boom')", /*feedback=*/false, 2.0, &t, &x);
  EXPECT_FALSE(outcome.ok);
  EXPECT_NEAR(outcome.t_reached, 0.5, 0.01);
  EXPECT_THAT(outcome.failure, HasSubstr("block 'f': expression error at t = "));
  EXPECT_THAT(outcome.failure, HasSubstr("block 'f':1: boom"));
  // the rows up to the failure are kept
  ASSERT_FALSE(x.empty());
  EXPECT_NEAR(x.back(), t.back(), 1e-6);
}

}  // namespace
}  // namespace mechflow::scripting
