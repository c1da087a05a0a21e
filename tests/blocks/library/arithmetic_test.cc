// gain, sum and product: values (scalar and elementwise), port names and
// feedthrough, division by zero, and factory errors.

#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/blocks/block_test_util.h"
#include "tests/numbers.h"

namespace mechflow::blocks {
namespace {

using ::testing::HasSubstr;
using testing::Blocks;
using testing::MakeBlock;
using testing::MakeError;
using testing::Options;
using testing::Simulate;

using mechflow::testing::kPi;

// a = (3, -1), b = (4, 0.5): every block elementwise on width 2.
TEST(ArithmeticTest, ElementwiseValues) {
  const auto run = Simulate(
      Blocks(MakeBlock("constant", "a", {{"value", "3 -1"}}), MakeBlock("constant", "b", {{"value", "4 0.5"}}),
             MakeBlock("gain", "g", {{"k", "-2.5"}, {"width", "2"}}),
             MakeBlock("sum", "s", {{"signs", "+-+"}, {"width", "2"}}),
             MakeBlock("product", "p", {{"operations", "**/"}, {"width", "2"}}),
             MakeBlock("product", "p2", {{"inputs", "3"}, {"width", "2"}})),
      {{"a", "g"}, {"a", "s.u1"}, {"b", "s.u2"}, {"g", "s.u3"}, {"a", "p.u1"}, {"b", "p.u2"}, {"g", "p.u3"},
       {"a", "p2.u1"}, {"b", "p2.u2"}, {"g", "p2.u3"}},
      {"g.y", "s.y", "p.y", "p2.y"}, Options(0.1, 0.1));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const double a[] = {3, -1}, b[] = {4, 0.5};
  for (int i = 0; i < 2; ++i) {
    const std::string k = "[" + std::to_string(i) + "]";
    const double g = -2.5 * a[i];
    EXPECT_DOUBLE_EQ(run.Column("g.y" + k).back(), g);
    EXPECT_DOUBLE_EQ(run.Column("s.y" + k).back(), a[i] - b[i] + g);
    EXPECT_DOUBLE_EQ(run.Column("p.y" + k).back(), a[i] * b[i] / g);
    EXPECT_DOUBLE_EQ(run.Column("p2.y" + k).back(), a[i] * b[i] * g);
  }
}

// Time-varying inputs: y = 2 sin(2 pi t) - t and y = sin(2 pi t) / (1 + t).
TEST(ArithmeticTest, FollowTimeVaryingInputs) {
  const auto run = Simulate(Blocks(MakeBlock("sine", "s"), MakeBlock("clock", "t"),
                                   MakeBlock("constant", "one", {{"value", "1"}}), MakeBlock("gain", "g", {{"k", "2"}}),
                                   MakeBlock("sum", "d", {{"signs", "+-"}}), MakeBlock("sum", "den"),
                                   MakeBlock("product", "q", {{"operations", "*/"}})),
                            {{"s", "g"}, {"g", "d.u1"}, {"t", "d.u2"}, {"one", "den.u1"}, {"t", "den.u2"},
                             {"s", "q.u1"}, {"den", "q.u2"}},
                            {"d.y", "q.y"}, Options(1.0, 0.01));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto t = run.Time(), d = run.Column("d.y"), q = run.Column("q.y");
  for (size_t i = 0; i < t.size(); ++i) {
    const double s = std::sin(2 * kPi * t[i]);
    EXPECT_NEAR(d[i], 2 * s - t[i], 1e-14);
    EXPECT_NEAR(q[i], s / (1 + t[i]), 1e-15);
  }
}

TEST(ArithmeticTest, PortNamesAndFeedthrough) {
  const auto one = MakeBlock("sum", "s", {{"signs", "-"}});
  ASSERT_EQ(one->num_inputs(), 1);
  EXPECT_EQ(one->input_port(0).name, "u");  // a single input is `u`
  const auto three = MakeBlock("product", "p", {{"operations", "*/*"}});
  ASSERT_EQ(three->num_inputs(), 3);
  EXPECT_EQ(three->input_port(2).name, "u3");
  EXPECT_EQ(MakeBlock("product", "p")->num_inputs(), 2);  // default: u1 u2
  for (const auto* b : {one.get(), three.get()})
    for (int in = 0; in < b->num_inputs(); ++in) EXPECT_TRUE(b->HasFeedthrough(in, 0));
  EXPECT_TRUE(MakeBlock("gain", "g", {{"k", "1"}})->HasFeedthrough(0, 0));
}

TEST(ArithmeticTest, DivisionByZeroFailsTheRunNamingTheBlockAndInput) {
  const auto run = Simulate(Blocks(MakeBlock("constant", "one", {{"value", "1"}}),
                                   MakeBlock("step", "r", {{"time", "0.5"}, {"before", "1"}, {"after", "0"}}),
                                   MakeBlock("product", "q", {{"operations", "*/"}}), MakeBlock("integrator", "x")),
                            {{"one", "q.u1"}, {"r", "q.u2"}, {"q", "x"}}, {"x.y"}, Options(1.0, 0.1));
  EXPECT_FALSE(run.outcome.ok);
  EXPECT_THAT(run.outcome.failure, HasSubstr("block 'q': division by zero (input u2 is 0) at t = 0.5"));
  // the rows before the failure are kept
  const auto t = run.Time(), x = run.Column("x.y");
  ASSERT_GE(t.size(), 5u);
  EXPECT_LE(t.back(), 0.5);
  EXPECT_NEAR(x.back(), t.back(), 1e-12);
}

TEST(ArithmeticTest, FactoriesRejectUnusableParameters) {
  EXPECT_EQ(MakeError("sum", {{"signs", "+*"}}), "'signs' may contain only the characters \"+-\", got \"+*\"");
  EXPECT_EQ(MakeError("sum", {{"signs", " "}}), "'signs' must name at least one input");
  EXPECT_EQ(MakeError("product", {{"operations", "*x"}}),
            "'operations' may contain only the characters \"*/\", got \"*x\"");
  EXPECT_EQ(MakeError("product", {{"inputs", "2"}, {"operations", "**/"}}),
            "'inputs' is 2 but 'operations' (\"**/\") names 3 inputs; give one of the two");
  EXPECT_EQ(MakeError("product", {{"inputs", "0"}}), "'inputs' must be a whole number >= 1, got 0");
  EXPECT_EQ(MakeError("gain", {{"k", "1"}, {"width", "1.5"}}), "'width' must be a whole number >= 1, got 1.5");
  EXPECT_EQ(MakeError("gain", {{"k", "inf"}}), "'k' must be a finite number, got inf");
}

}  // namespace
}  // namespace mechflow::blocks
