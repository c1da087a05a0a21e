// abs, saturation and dead_zone: outputs against closed forms, corners as
// events, and the awkward instants: an input that starts exactly on a corner
// and leaves it, and an input that jumps across corners at another block's
// event.

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "tests/blocks/block_test_util.h"
#include "tests/numbers.h"

namespace mechflow::blocks {
namespace {

using testing::Blocks;
using testing::MakeBlock;
using testing::MakeError;
using testing::Options;
using testing::Simulate;

using mechflow::testing::kPi;

// Closed forms, written out independently of the blocks.
double DeadZone(double u, double start, double end) { return u < start ? u - start : u > end ? u - end : 0.0; }

// How often u(t) crosses `level` in (0, t_end], counted on a fine grid.
template <typename F>
int Crossings(F u, double level, double t_end) {
  int n = 0;
  const int steps = 200000;
  for (int i = 1; i <= steps; ++i)
    n += (u(t_end * (i - 1) / steps) > level) != (u(t_end * i / steps) > level);
  return n;
}

TEST(DiscontinuitiesTest, FollowTheClosedFormsOfASine) {
  const auto run = Simulate(Blocks(MakeBlock("sine", "u", {{"amplitude", "2"}, {"frequency", "1.5"}}),
                                   MakeBlock("abs", "a"),
                                   MakeBlock("saturation", "sat", {{"lower", "-1"}, {"upper", "1.5"}}),
                                   MakeBlock("dead_zone", "dz", {{"start", "-0.5"}, {"end", "0.5"}})),
                            {{"u", "a"}, {"u", "sat"}, {"u", "dz"}}, {"a.y", "sat.y", "dz.y"}, Options(1.9, 0.001));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto t = run.Time(), a = run.Column("a.y"), sat = run.Column("sat.y"), dz = run.Column("dz.y");
  for (size_t i = 0; i < t.size(); ++i) {
    const double u = 2 * std::sin(2 * kPi * 1.5 * t[i]);
    // the sine block itself is exact to rounding; the blocks add no error
    EXPECT_NEAR(a[i], std::abs(u), 1e-12) << "t = " << t[i];
    EXPECT_NEAR(sat[i], std::clamp(u, -1.0, 1.5), 1e-12) << "t = " << t[i];
    EXPECT_NEAR(dz[i], DeadZone(u, -0.5, 0.5), 1e-12) << "t = " << t[i];
  }
  // every corner crossing is an event at the closed-form instant:
  // abs crosses 0 at t = k/3 (k = 1..5; t = 0 is the start, not a crossing)
  const auto abs_events = run.EventTimes("a");
  ASSERT_EQ(abs_events.size(), 5u);
  // CVODE locates a root to about 100 roundings of t (its ttol), and the
  // sine's zero is itself known to a few roundings
  for (size_t k = 0; k < abs_events.size(); ++k) EXPECT_NEAR(abs_events[k], (k + 1) / 3.0, 1e-12);
  // one event per corner crossing, no more (no chattering, no re-arming)
  const auto u = [](double t) { return 2 * std::sin(2 * kPi * 1.5 * t); };
  EXPECT_EQ(run.EventTimes("sat").size(), size_t(Crossings(u, -1.0, 1.9) + Crossings(u, 1.5, 1.9)));
  EXPECT_EQ(run.EventTimes("dz").size(), size_t(Crossings(u, -0.5, 1.9) + Crossings(u, 0.5, 1.9)));
}

// u = -t and u = t from t = 0: the input sits exactly on a corner at the start
// and leaves it. CVODE does not report a crossing function that starts at
// exactly zero, so the blocks must not put a crossing function at exactly zero
// on the boundary of the current mode.
TEST(DiscontinuitiesTest, InputLeavingACornerItStartsOn) {
  for (const double slope : {-1.0, 1.0}) {
    SCOPED_TRACE("slope " + std::to_string(slope));
    const auto run = Simulate(Blocks(MakeBlock("ramp", "u", {{"slope", std::to_string(slope)}}),
                                     MakeBlock("abs", "a"),
                                     MakeBlock("saturation", "lo", {{"lower", "0"}, {"upper", "1"}}),
                                     MakeBlock("saturation", "hi", {{"lower", "-1"}, {"upper", "0"}}),
                                     MakeBlock("dead_zone", "dz_lo", {{"start", "0"}, {"end", "0.5"}}),
                                     MakeBlock("dead_zone", "dz_hi", {{"start", "-0.5"}, {"end", "0"}})),
                              {{"u", "a"}, {"u", "lo"}, {"u", "hi"}, {"u", "dz_lo"}, {"u", "dz_hi"}},
                              {"u.y", "a.y", "lo.y", "hi.y", "dz_lo.y", "dz_hi.y"}, Options(1.0, 0.01));
    ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
    const auto u = run.Column("u.y"), a = run.Column("a.y"), lo = run.Column("lo.y"), hi = run.Column("hi.y"),
               dz_lo = run.Column("dz_lo.y"), dz_hi = run.Column("dz_hi.y");
    for (size_t i = 0; i < u.size(); ++i) {
      // the outputs are linear in u on each piece: exact up to rounding
      EXPECT_NEAR(a[i], std::abs(u[i]), 1e-14) << "u = " << u[i];
      EXPECT_NEAR(lo[i], std::clamp(u[i], 0.0, 1.0), 1e-14) << "u = " << u[i];
      EXPECT_NEAR(hi[i], std::clamp(u[i], -1.0, 0.0), 1e-14) << "u = " << u[i];
      EXPECT_NEAR(dz_lo[i], DeadZone(u[i], 0.0, 0.5), 1e-14) << "u = " << u[i];
      EXPECT_NEAR(dz_hi[i], DeadZone(u[i], -0.5, 0.0), 1e-14) << "u = " << u[i];
    }
  }
}

// u = step(0 -> 1 at 0.3) - ramp(slope 2 from 0.6): u jumps onto the upper
// corner of a saturation [-1, 1] at an event of the step, rests there, then
// leaves it downwards at the ramp's corner (another event), crossing the
// lower corner at t = 1.6.
TEST(DiscontinuitiesTest, InputJumpingOntoACornerAndLeavingIt) {
  const auto run = Simulate(Blocks(MakeBlock("step", "s", {{"time", "0.3"}}),
                                   MakeBlock("ramp", "r", {{"slope", "2"}, {"start", "0.6"}}),
                                   MakeBlock("sum", "u", {{"signs", "+-"}}),
                                   MakeBlock("saturation", "sat", {{"lower", "-1"}, {"upper", "1"}}),
                                   MakeBlock("step", "jump", {{"time", "0.45"}, {"before", "-3"}, {"after", "3"}}),
                                   MakeBlock("saturation", "sat2", {{"lower", "-1"}, {"upper", "1"}})),
                            {{"s", "u.u1"}, {"r", "u.u2"}, {"u", "sat"}, {"jump", "sat2"}},
                            {"u.y", "sat.y", "sat2.y"}, Options(2.0, 0.01));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto t = run.Time(), u = run.Column("u.y"), sat = run.Column("sat.y"), sat2 = run.Column("sat2.y");
  for (size_t i = 0; i < t.size(); ++i) {
    const double expected_u = (t[i] >= 0.3 ? 1.0 : 0.0) - (t[i] >= 0.6 ? 2 * (t[i] - 0.6) : 0.0);
    EXPECT_NEAR(u[i], expected_u, 1e-12) << "t = " << t[i];
    EXPECT_NEAR(sat[i], std::clamp(expected_u, -1.0, 1.0), 1e-12) << "t = " << t[i];
    // a jump straight across both corners: re-classified after the step's event
    EXPECT_EQ(sat2[i], t[i] >= 0.45 ? 1.0 : -1.0) << "t = " << t[i];
  }
  // the only continuous corner crossing of sat is u = -1 at t = 1.6
  const auto events = run.EventTimes("sat");
  ASSERT_EQ(events.size(), 1u);
  EXPECT_NEAR(events[0], 1.6, 1e-12);
  EXPECT_TRUE(run.EventTimes("sat2").empty());
}

TEST(DiscontinuitiesTest, VectorsAreElementwise) {
  const auto run = Simulate(Blocks(MakeBlock("constant", "c", {{"value", "-2 0.25 3"}}),
                                   MakeBlock("abs", "a", {{"width", "3"}}),
                                   MakeBlock("saturation", "s", {{"lower", "-1"}, {"upper", "1"}, {"width", "3"}}),
                                   MakeBlock("dead_zone", "d", {{"start", "-1"}, {"end", "1"}, {"width", "3"}})),
                            {{"c", "a"}, {"c", "s"}, {"c", "d"}}, {"a.y", "s.y", "d.y"}, Options(0.1, 0.1));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const int last = run.results().num_rows() - 1;
  const double a[] = {2, 0.25, 3}, s[] = {-1, 0.25, 1}, d[] = {-1, 0, 2};
  for (int i = 0; i < 3; ++i) {
    const std::string k = "[" + std::to_string(i) + "]";
    EXPECT_EQ(run.Column("a.y" + k)[last], a[i]);
    EXPECT_EQ(run.Column("s.y" + k)[last], s[i]);
    EXPECT_EQ(run.Column("d.y" + k)[last], d[i]);
  }
}

// u = sin(6 pi t) - sin(6 pi t + 2 pi): zero up to round-off, its sign
// flipping at random. Every switching block resting on a corner at 0 keeps
// its piece (hysteresis.h) instead of switching at each flip (94 events in
// 0.5 s without the band).
TEST(DiscontinuitiesTest, ASignalRestingOnACornerDoesNotChatter) {
  const auto run = Simulate(
      Blocks(MakeBlock("sine", "s1", {{"frequency", "3"}}),
             MakeBlock("sine", "s2", {{"frequency", "3"}, {"phase", testing::Num(2 * kPi)}}),
             MakeBlock("sum", "u", {{"signs", "+-"}}), MakeBlock("abs", "a"),
             MakeBlock("saturation", "sat", {{"lower", "0"}, {"upper", "1"}}),
             MakeBlock("dead_zone", "dz", {{"start", "0"}, {"end", "1"}}),
             MakeBlock("lookup", "f", {{"points", "-1 1; 0 0; 1 1"}}),
             MakeBlock("integrator", "i", {{"upper", "0"}})),
      {{"s1", "u.u1"}, {"s2", "u.u2"}, {"u", "a"}, {"u", "sat"}, {"u", "dz"}, {"u", "f"}, {"u", "i"}},
      {"u.y", "a.y", "i.y"}, Options(0.5, 0.01));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto u = run.Column("u.y");
  // the input does flip sign: the test would catch chatter
  EXPECT_TRUE(std::any_of(u.begin(), u.end(), [](double v) { return v > 0; }));
  EXPECT_TRUE(std::any_of(u.begin(), u.end(), [](double v) { return v < 0; }));
  EXPECT_EQ(run.sim->stats().events, 0);
  for (const double y : run.Column("a.y")) EXPECT_LT(y, 1e-12);
}

TEST(DiscontinuitiesTest, FactoriesRejectUnusableParameters) {
  EXPECT_EQ(MakeError("saturation", {{"lower", "1"}, {"upper", "1"}}), "'lower' must be less than 'upper'");
  EXPECT_EQ(MakeError("dead_zone", {{"start", "2"}, {"end", "1"}}), "'start' must be less than 'end'");
  EXPECT_EQ(MakeError("abs", {{"width", "0"}}), "'width' must be a whole number >= 1, got 0");
}

}  // namespace
}  // namespace mechflow::blocks
