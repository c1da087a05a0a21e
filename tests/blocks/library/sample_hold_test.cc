// sample_hold (and recorder, the other sink-like block): updates exactly at
// offset + k period, holds in between, no feedthrough; recorder ports.

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

// Sampling the clock shows the sample time itself: at any row t the held
// value is the last hit t_k = offset + k period <= t, or `initial` before the
// first hit. The grid (0.001) puts rows on both sides of every hit.
TEST(SampleHoldTest, UpdatesExactlyAtOffsetPlusMultiplesOfThePeriod) {
  const double period = 0.1, offset = 0.05;
  const auto run = Simulate(Blocks(MakeBlock("clock", "clk"),
                                   MakeBlock("sample_hold", "h",
                                             {{"period", "0.1"}, {"offset", "0.05"}, {"initial", "-1"}})),
                            {{"clk", "h"}}, {"h.y"}, Options(1.0, 0.001));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto t = run.Time(), held = run.Column("h.y");
  ASSERT_EQ(t.size(), 1001u);
  for (size_t i = 0; i < t.size(); ++i) {
    // the hit times as the simulator computes them: offset + k period, as
    // the decimal it stands for (0.15, not 0.05 + 0.1 = 0.15000000000000002)
    double expected = -1.0;
    for (long k = 0; offset + k * period <= t[i] + 1e-12; ++k) expected = std::round((offset + k * period) * 1e6) / 1e6;
    // the clock is sampled exactly at t_k, so the held value is t_k itself
    EXPECT_EQ(held[i], expected) << "t = " << t[i];
  }
  EXPECT_EQ(run.sim->stats().sample_hits, 10);
}

// A hit at t_end is taken before the last row, also when rounding puts it a
// hair past t_end (3 * 0.1 = 0.30000000000000004 > 0.3): the rows were once
// 0, 0.1, 0.2, 0.2.
TEST(SampleHoldTest, AHitAtTheEndIsInTheLastRow) {
  for (const double t_end : {0.3, 1.0}) {
    const auto run = Simulate(Blocks(MakeBlock("clock", "clk"), MakeBlock("sample_hold", "h", {{"period", "0.1"}})),
                              {{"clk", "h"}}, {"h.y"}, Options(t_end, 0.1));
    ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
    const auto t = run.Time(), held = run.Column("h.y");
    ASSERT_EQ(t.size(), static_cast<size_t>(std::lround(t_end / 0.1)) + 1);
    for (size_t i = 0; i < t.size(); ++i) EXPECT_NEAR(held[i], t[i], 1e-12) << "t = " << t[i];
    EXPECT_EQ(run.sim->stats().sample_hits, std::lround(t_end / 0.1) + 1) << "t_end = " << t_end;
  }
}

// y depends on u only through the hits: a loop through the hold is not
// algebraic. x_{k+1} = x_k / 2 + 1 sampled every 0.25 s from x = 0.
TEST(SampleHoldTest, BreaksAFeedbackLoop) {
  const auto run = Simulate(Blocks(MakeBlock("constant", "one", {{"value", "1"}}),
                                   MakeBlock("gain", "half", {{"k", "0.5"}}), MakeBlock("sum", "next"),
                                   MakeBlock("sample_hold", "x", {{"period", "0.25"}})),
                            {{"x", "half"}, {"half", "next.u1"}, {"one", "next.u2"}, {"next", "x"}}, {"x.y"},
                            Options(1.1, 0.1));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto t = run.Time(), x = run.Column("x.y");
  for (size_t i = 0; i < t.size(); ++i) {
    // hits at 0, 0.25, ... (a row at a hit shows the value after it); from
    // x = 0 the first samples 0 / 2 + 1 = 1, then 1.5, 1.75: after h hits
    // x = 2 - 2^(1 - h)
    const int hits = static_cast<int>(std::floor(t[i] / 0.25 + 1e-9)) + 1;
    EXPECT_DOUBLE_EQ(x[i], 2 - std::pow(2.0, 1 - hits)) << "t = " << t[i];
  }
  EXPECT_FALSE(MakeBlock("sample_hold", "h", {{"period", "1"}})->HasFeedthrough(0, 0));
}

TEST(SampleHoldTest, VectorHold) {
  const auto h = MakeBlock("sample_hold", "h", {{"period", "1"}, {"initial", "1 2 3"}});
  EXPECT_EQ(h->input_port(0).width, 3);
  EXPECT_EQ(h->num_discrete_states(), 3);
  EXPECT_EQ(h->sample_time().period, 1.0);
}

TEST(SampleHoldTest, FactoryRejectsUnusableParameters) {
  EXPECT_EQ(MakeError("sample_hold", {{"period", "0"}}), "'period' must be > 0");
  EXPECT_EQ(MakeError("sample_hold", {{"period", "-1"}}), "'period' must be > 0");
  EXPECT_EQ(MakeError("sample_hold", {{"period", "1"}, {"offset", "-0.5"}}), "'offset' must be >= 0");
}

TEST(RecorderTest, DeclaresInputsOnly) {
  const auto one = MakeBlock("recorder", "r");
  ASSERT_EQ(one->num_inputs(), 1);
  EXPECT_EQ(one->input_port(0).name, "u");
  EXPECT_EQ(one->num_outputs(), 0);
  const auto three = MakeBlock("recorder", "r", {{"inputs", "3"}, {"width", "2"}});
  ASSERT_EQ(three->num_inputs(), 3);
  EXPECT_EQ(three->input_port(0).name, "u1");
  EXPECT_EQ(three->input_port(2).name, "u3");
  EXPECT_EQ(three->input_port(2).width, 2);
  EXPECT_EQ(MakeError("recorder", {{"inputs", "0"}}), "'inputs' must be a whole number >= 1, got 0");
  // a recorder in a diagram: its inputs must be driven, it computes nothing
  const auto run = Simulate(Blocks(MakeBlock("clock", "clk"), MakeBlock("recorder", "rec")), {{"clk", "rec"}},
                            {"clk.y"}, Options(1.0, 0.5));
  EXPECT_TRUE(run.outcome.ok) << run.outcome.failure;
}

}  // namespace
}  // namespace mechflow::blocks
