// first_order_lag: step responses against K u + (y0 - K u) exp(-t/T).

#include <cmath>

#include <gtest/gtest.h>

#include "tests/blocks/block_test_util.h"

namespace mechflow::blocks {
namespace {

using testing::Blocks;
using testing::MakeBlock;
using testing::MakeError;
using testing::Options;
using testing::Simulate;

// u = 1 from t = 0; T = 0.3 s, K = 2: element 0 from y0 = 0, element 1 from y0 = 5.
TEST(FirstOrderLagTest, StepResponseMatchesClosedForm) {
  const auto run = Simulate(Blocks(MakeBlock("constant", "u", {{"value", "1 1"}}),
                                   MakeBlock("first_order_lag", "lag",
                                             {{"time_constant", "0.3"}, {"gain", "2"}, {"initial", "0 5"}})),
                            {{"u", "lag"}}, {"lag.y"}, Options(2.0, 0.01));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto t = run.Time(), y0 = run.Column("lag.y[0]"), y1 = run.Column("lag.y[1]");
  for (size_t i = 0; i < t.size(); ++i) {
    const double decay = std::exp(-t[i] / 0.3);
    // global error of BDF at rtol 1e-10, atol 1e-12 on values of order 1..5
    EXPECT_NEAR(y0[i], 2 * (1 - decay), 1e-8) << "t = " << t[i];
    EXPECT_NEAR(y1[i], 2 + 3 * decay, 1e-8) << "t = " << t[i];
  }
}

// The lag's output is its state: a loop through it is not algebraic.
// y' = (K (r - y) - y) / T with r = 1: y -> K / (1 + K) with rate (1 + K) / T.
TEST(FirstOrderLagTest, BreaksAFeedbackLoop) {
  const auto run = Simulate(Blocks(MakeBlock("constant", "r", {{"value", "1"}}),
                                   MakeBlock("sum", "e", {{"signs", "+-"}}),
                                   MakeBlock("first_order_lag", "lag", {{"time_constant", "0.5"}, {"gain", "3"}})),
                            {{"r", "e.u1"}, {"lag", "e.u2"}, {"e", "lag"}}, {"lag.y"}, Options(2.0, 0.05));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto t = run.Time(), y = run.Column("lag.y");
  for (size_t i = 0; i < t.size(); ++i)
    EXPECT_NEAR(y[i], 0.75 * (1 - std::exp(-8 * t[i])), 1e-8) << "t = " << t[i];
  EXPECT_FALSE(MakeBlock("first_order_lag", "l", {{"time_constant", "1"}})->HasFeedthrough(0, 0));
}

TEST(FirstOrderLagTest, FactoryRejectsUnusableParameters) {
  EXPECT_EQ(MakeError("first_order_lag", {{"time_constant", "0"}}), "'time_constant' must be > 0");
  EXPECT_EQ(MakeError("first_order_lag", {{"time_constant", "-1"}}), "'time_constant' must be > 0");
  EXPECT_EQ(MakeError("first_order_lag", {{"time_constant", "1"}, {"initial", "1 2"}, {"width", "3"}}),
            "'initial' has 2 values but the width is 3");
}

}  // namespace
}  // namespace mechflow::blocks
