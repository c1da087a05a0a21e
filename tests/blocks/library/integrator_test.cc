// integrator: ramps, limits (entering, resting, leaving) and resets, each
// against a closed form; event times against their closed-form instants.

#include <cmath>

#include <gtest/gtest.h>

#include "tests/blocks/block_test_util.h"
#include "tests/numbers.h"

namespace mechflow::blocks {
namespace {

using testing::Blocks;
using testing::MakeBlock;
using testing::MakeError;
using testing::Num;
using testing::Options;
using testing::Simulate;

using mechflow::testing::kPi;

// True when t is an event instant: the row there may show the value just
// before the event (the root is located at or a hair after t) or after it.
bool AtEvent(double t, std::initializer_list<double> events) {
  for (const double e : events)
    if (std::abs(t - e) < 1e-9) return true;
  return false;
}

TEST(IntegratorTest, ConstantInputGivesARamp) {
  const auto run = Simulate(Blocks(MakeBlock("constant", "c", {{"value", "3 0.5"}}),
                                   MakeBlock("integrator", "x", {{"initial", "1 -2"}})),
                            {{"c", "x"}}, {"x.y"}, Options(2.0, 0.1));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto t = run.Time(), x0 = run.Column("x.y[0]"), x1 = run.Column("x.y[1]");
  ASSERT_EQ(t.size(), 21u);
  for (size_t i = 0; i < t.size(); ++i) {
    // BDF reproduces a linear solution up to rounding
    EXPECT_NEAR(x0[i], 1 + 3 * t[i], 1e-12);
    EXPECT_NEAR(x1[i], -2 + 0.5 * t[i], 1e-12);
  }
}

TEST(IntegratorTest, OneInitialValueIsRepeatedToTheWidth) {
  const auto x = MakeBlock("integrator", "x", {{"initial", "4"}, {"width", "3"}});
  EXPECT_EQ(x->input_port(0).width, 3);
  EXPECT_EQ(x->output_port(0).width, 3);
  EXPECT_EQ(x->num_states(), 3);
  EXPECT_FALSE(x->HasFeedthrough(0, 0));
}

// u = 1 until t = 2, then -1 (a step). With upper = 1 and lower = -0.5:
// x = t up to t = 1 (limit reached: an event of x), x = 1 exactly until the
// step turns u at t = 2, then x = 1 - (t - 2) down to -0.5 at t = 3.5.
TEST(IntegratorTest, LimitsHoldExactlyAndReleaseWhenTheInputTurns) {
  const auto run = Simulate(Blocks(MakeBlock("step", "u", {{"time", "2"}, {"before", "1"}, {"after", "-1"}}),
                                   MakeBlock("integrator", "x", {{"upper", "1"}, {"lower", "-0.5"}})),
                            {{"u", "x"}}, {"x.y"}, Options(4.0, 0.01));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto t = run.Time(), x = run.Column("x.y");
  for (size_t i = 0; i < t.size(); ++i) {
    if (AtEvent(t[i], {1.0, 3.5})) continue;
    if (t[i] > 1.0 && t[i] <= 2.0) {
      // set exactly to the limit at the event, then x' = 0
      EXPECT_EQ(x[i], 1.0) << "t = " << t[i];
    } else if (t[i] > 3.5) {
      EXPECT_EQ(x[i], -0.5) << "t = " << t[i];
    } else {
      // piecewise linear: exact up to rounding and the located event times
      EXPECT_NEAR(x[i], t[i] < 1 ? t[i] : 1 - (t[i] - 2), 1e-11) << "t = " << t[i];
    }
  }
  // the two limit hits are the integrator's own events; leaving the upper
  // limit happened at the step's event (the input jumped)
  const auto events = run.EventTimes("x");
  ASSERT_EQ(events.size(), 2u);
  // CVODE locates a root to about 100 roundings of t
  EXPECT_NEAR(events[0], 1.0, 1e-12);
  EXPECT_NEAR(events[1], 3.5, 1e-12);
}

// x' = cos t from x(0) = upper = 1: at the limit from the start; u turns
// negative at t = pi/2 (an event of x), then x = sin t.
TEST(IntegratorTest, StartsOnItsLimitAndLeavesWhenTheInputChangesSign) {
  const auto run = Simulate(Blocks(MakeBlock("sine", "u", {{"frequency", Num(1 / (2 * kPi))},
                                                            {"phase", Num(kPi / 2)}}),
                                   MakeBlock("integrator", "x", {{"initial", "1"}, {"upper", "1"}})),
                            {{"u", "x"}}, {"x.y"}, Options(4.0, 0.01));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto t = run.Time(), x = run.Column("x.y");
  for (size_t i = 0; i < t.size(); ++i) {
    if (t[i] <= kPi / 2) {
      EXPECT_EQ(x[i], 1.0) << "t = " << t[i];
    } else {
      // rtol 1e-10 on values of order 1, over a few hundred steps
      EXPECT_NEAR(x[i], std::sin(t[i]), 1e-8) << "t = " << t[i];
    }
  }
  const auto events = run.EventTimes("x");
  ASSERT_EQ(events.size(), 1u);
  // cos t is computed as sin(t + pi/2): its zero is known to ~1e-15, and
  // CVODE locates the root to about 100 roundings of t; the limit lets go
  // once u is past the hysteresis band, 1e-12 (u' = -1 there)
  EXPECT_NEAR(events[0], kPi / 2 + 1e-12, 3e-13);
}

// The input rests at exactly 0 while x sits on its upper limit (u = step
// 1 -> 0 at t = 1.5), then leaves 0 at t = 3 (a ramp corner): pushing into
// the limit (slope +1) keeps x there; pulling away (slope -1) releases it.
TEST(IntegratorTest, InputRestingAtZeroOnALimit) {
  for (const double slope : {1.0, -1.0}) {
    SCOPED_TRACE("slope " + std::to_string(slope));
    const auto run = Simulate(Blocks(MakeBlock("step", "s", {{"time", "1.5"}, {"before", "1"}, {"after", "0"}}),
                                     MakeBlock("ramp", "r", {{"slope", std::to_string(slope)}, {"start", "3"}}),
                                     MakeBlock("sum", "u"), MakeBlock("integrator", "x", {{"upper", "1"}})),
                              {{"s", "u.u1"}, {"r", "u.u2"}, {"u", "x"}}, {"x.y"}, Options(4.0, 0.01));
    ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
    const auto t = run.Time(), x = run.Column("x.y");
    for (size_t i = 0; i < t.size(); ++i) {
      double expected = std::min(t[i], 1.0);
      if (slope < 0 && t[i] > 3) expected = 1 - 0.5 * (t[i] - 3) * (t[i] - 3);
      // the quadratic after t = 3 starts with low-order BDF steps, each within
      // the local tolerance rtol = 1e-10 of values of order 1
      EXPECT_NEAR(x[i], expected, 1e-9) << "t = " << t[i];
      EXPECT_LE(x[i], 1.0) << "t = " << t[i];
    }
  }
}

// The bouncing ball: v' = -g, p' = v from p(0) = h; when p falls through 0
// the velocity is reset to x0 = -e v (read just before the impact).
// Impacts: t1 = sqrt(2 h / g), then t(n+1) = t(n) + 2 e^n g t1 / g.
TEST(IntegratorTest, ResetBouncingBall) {
  const double g = 9.81, h = 1.0, e = 0.8;
  const auto run = Simulate(Blocks(MakeBlock("constant", "gravity", {{"value", Num(-g)}}),
                                   MakeBlock("integrator", "v", {{"reset", "falling"}}),
                                   MakeBlock("integrator", "p", {{"initial", Num(h)}}),
                                   MakeBlock("gain", "rebound", {{"k", Num(-e)}})),
                            {{"gravity", "v.u"}, {"v", "p"}, {"p", "v.reset"}, {"v", "rebound"}, {"rebound", "v.x0"}},
                            {"p.y", "v.y"}, Options(2.0, 0.001));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const double t1 = std::sqrt(2 * h / g);
  const double impacts[] = {t1, t1 + 2 * e * t1, t1 + 2 * e * t1 + 2 * e * e * t1};
  // one event per impact: the rebound through p = 0 upwards is not an event
  const auto events = run.EventTimes("v");
  ASSERT_EQ(events.size(), 3u);
  // the solution is piecewise quadratic, so the solver's interpolant is
  // nearly exact and the impact times are limited by the root location
  // (~1e-13) and rtol: 1e-9 is ample (the task asked for 1e-6 s)
  for (int n = 0; n < 3; ++n) EXPECT_NEAR(events[n], impacts[n], 1e-9) << "impact " << n + 1;
  // between the first two impacts: v = e g t1 - g (t - t1)
  const auto t = run.Time(), v = run.Column("v.y"), p = run.Column("p.y");
  for (size_t i = 0; i < t.size(); ++i) {
    if (t[i] > impacts[0] && t[i] < impacts[1]) {
      EXPECT_NEAR(v[i], e * g * t1 - g * (t[i] - t1), 1e-8) << "t = " << t[i];
      EXPECT_NEAR(p[i], e * g * t1 * (t[i] - t1) - 0.5 * g * (t[i] - t1) * (t[i] - t1), 1e-8) << "t = " << t[i];
    }
    EXPECT_GT(p[i], -1e-9) << "t = " << t[i];
  }
}

// A trigger that is exactly 0 where the integration starts and then rises
// continuously gives no crossing (CVODE does not report a crossing function
// that starts at exactly zero); this is documented in integrator.h. Its next
// rise through zero does reset.
TEST(IntegratorTest, TriggerLeavingExactZeroAtTheStartIsNoCrossing) {
  const auto run = Simulate(Blocks(MakeBlock("constant", "one", {{"value", "1"}}),
                                   MakeBlock("constant", "five", {{"value", "5"}}), MakeBlock("sine", "trigger"),
                                   MakeBlock("integrator", "x", {{"reset", "rising"}})),
                            {{"one", "x.u"}, {"trigger", "x.reset"}, {"five", "x.x0"}}, {"x.y"}, Options(1.5, 0.25));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto events = run.EventTimes("x");
  ASSERT_EQ(events.size(), 1u);
  EXPECT_NEAR(events[0], 1.0, 1e-12);
  const auto t = run.Time(), x = run.Column("x.y");
  for (size_t i = 0; i < t.size(); ++i) {
    if (AtEvent(t[i], {1.0})) continue;
    EXPECT_NEAR(x[i], t[i] < 1 ? t[i] : 5 + (t[i] - 1), 1e-11) << "t = " << t[i];
  }
}

// A trigger that jumps across zero at another block's event (a step) resets
// too; x0 is read at the reset. u = 1, x0 = 5.
TEST(IntegratorTest, ResetByASteppedTrigger) {
  struct Case {
    const char* reset;
    const char* before;
    const char* after;
    bool resets;
  };
  const Case cases[] = {{"rising", "0", "1", true},    {"rising", "-1", "1", true}, {"rising", "1", "-1", false},
                        {"falling", "1", "-1", true},  {"falling", "0", "-1", true}, {"falling", "-1", "1", false},
                        {"either", "-1", "1", true},   {"either", "1", "-1", true},  {"rising", "-1", "0", false}};
  for (const Case& c : cases) {
    SCOPED_TRACE(std::string(c.reset) + " " + c.before + " -> " + c.after);
    const auto run = Simulate(
        Blocks(MakeBlock("constant", "one", {{"value", "1"}}), MakeBlock("constant", "five", {{"value", "5"}}),
               MakeBlock("step", "trigger", {{"time", "1"}, {"before", c.before}, {"after", c.after}}),
               MakeBlock("integrator", "x", {{"reset", c.reset}})),
        {{"one", "x.u"}, {"trigger", "x.reset"}, {"five", "x.x0"}}, {"x.y"}, Options(2.0, 0.25));
    ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
    const auto t = run.Time(), x = run.Column("x.y");
    for (size_t i = 0; i < t.size(); ++i) {
      // the row at t = 1 is taken after the step's event (located exactly at 1)
      const double expected = (c.resets && t[i] >= 1.0) ? 5 + (t[i] - 1) : t[i];
      EXPECT_NEAR(x[i], expected, 1e-12) << "t = " << t[i];
    }
  }
}

// x0 = -x, read just before each reset: the reset flips the sign of x.
// u = 1, trigger = -cos(2 pi t) = sin(2 pi t - pi/2) (rising): resets at
// t = 0.25 and 1.25 only (falling through zero is not a trigger).
TEST(IntegratorTest, ResetReadsX0JustBeforeTheReset) {
  const auto run = Simulate(Blocks(MakeBlock("constant", "one", {{"value", "1"}}),
                                   MakeBlock("sine", "trigger", {{"phase", Num(-kPi / 2)}}),
                                   MakeBlock("integrator", "x", {{"reset", "rising"}, {"initial", "0.25"}}),
                                   MakeBlock("gain", "flip", {{"k", "-1"}})),
                            {{"one", "x.u"}, {"trigger", "x.reset"}, {"x", "flip"}, {"flip", "x.x0"}}, {"x.y"},
                            Options(2.0, 0.05));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto events = run.EventTimes("x");
  ASSERT_EQ(events.size(), 2u);
  // the zero of the sine block is known to ~1e-15, CVODE's root to ~1e-13
  EXPECT_NEAR(events[0], 0.25, 1e-12);
  EXPECT_NEAR(events[1], 1.25, 1e-12);
  // x = 0.25 + t; at 0.25: -0.5, then -0.5 + (t - 0.25) = 0.5 at 1.25: -0.5 again
  const auto t = run.Time(), x = run.Column("x.y");
  for (size_t i = 0; i < t.size(); ++i) {
    if (AtEvent(t[i], {0.25, 1.25})) continue;
    const double expected = t[i] < 0.25 ? 0.25 + t[i] : t[i] < 1.25 ? -0.5 + (t[i] - 0.25) : -0.5 + (t[i] - 1.25);
    // the event instants are located to ~1e-13, the rows in between are exact
    EXPECT_NEAR(x[i], expected, 1e-10) << "t = " << t[i];
  }
}

TEST(IntegratorTest, ResetAddsTheTriggerAndX0Inputs) {
  const auto x = MakeBlock("integrator", "x", {{"reset", "either"}, {"width", "2"}});
  ASSERT_EQ(x->num_inputs(), 3);
  EXPECT_EQ(x->input_port(1).name, "reset");
  EXPECT_EQ(x->input_port(1).width, 1);
  EXPECT_EQ(x->input_port(2).name, "x0");
  EXPECT_EQ(x->input_port(2).width, 2);
  // no input feeds y directly: x0 is read only at the reset instant
  for (int in = 0; in < 3; ++in) EXPECT_FALSE(x->HasFeedthrough(in, 0));
}

TEST(IntegratorTest, FactoryRejectsUnusableParameters) {
  EXPECT_EQ(MakeError("integrator", {{"reset", "up"}}), "'reset' must be rising, falling or either, got 'up'");
  EXPECT_EQ(MakeError("integrator", {{"lower", "1"}, {"upper", "0"}}), "'lower' must be less than 'upper'");
  EXPECT_EQ(MakeError("integrator", {{"initial", "1 2"}, {"width", "3"}}), "'initial' has 2 values but the width is 3");
  EXPECT_EQ(MakeError("integrator", {{"initial", "2"}, {"upper", "1"}}), "'initial' (2) is above 'upper' (1)");
  EXPECT_EQ(MakeError("integrator", {{"initial", "0 -3"}, {"lower", "-1"}}), "'initial' (-3) is below 'lower' (-1)");
}

}  // namespace
}  // namespace mechflow::blocks
