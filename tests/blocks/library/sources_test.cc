// Sources (constant, clock, step, ramp, sine, table): values against their
// formulas, the step and the ramp corner as events, and tables read inline
// or from CSV, with bad tables rejected naming the row.

#include <cmath>
#include <cstdio>
#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "blocks/library/table.h"
#include "tests/blocks/block_test_util.h"
#include "tests/numbers.h"

namespace mechflow::blocks {
namespace {

using ::testing::HasSubstr;
using testing::Blocks;
using testing::MakeBlock;
using testing::MakeError;
using testing::Num;
using testing::Options;
using testing::Simulate;

using mechflow::testing::kPi;

TEST(SourcesTest, ConstantClockAndSine) {
  const auto run = Simulate(Blocks(MakeBlock("constant", "c", {{"value", "1.5 -2"}}), MakeBlock("clock", "clk"),
                                   MakeBlock("sine", "s", {{"amplitude", "3"},
                                                           {"frequency", "0.5"},
                                                           {"phase", "0.25"},
                                                           {"bias", "1"}})),
                            {}, {"c.y", "clk.y", "s.y"}, Options(2.0, 0.01));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto t = run.Time(), c0 = run.Column("c.y[0]"), c1 = run.Column("c.y[1]"), clk = run.Column("clk.y"),
             s = run.Column("s.y");
  ASSERT_EQ(t.size(), 201u);
  for (size_t i = 0; i < t.size(); ++i) {
    EXPECT_EQ(c0[i], 1.5);
    EXPECT_EQ(c1[i], -2.0);
    EXPECT_EQ(clk[i], t[i]);
    // the same formula, evaluated independently: equal to rounding
    EXPECT_NEAR(s[i], 1 + 3 * std::sin(2 * kPi * 0.5 * t[i] + 0.25), 1e-14) << "t = " << t[i];
  }
}

// x' = step(0.35, 0 -> 2): the step is an event at exactly t = 0.35, y is
// `before` strictly before and `after` from then on, and since the right-hand
// side is constant on both sides the solver needs only a few steps.
TEST(SourcesTest, StepIsAnEventWithExactValuesOnBothSides) {
  const auto run = Simulate(Blocks(MakeBlock("step", "s", {{"time", "0.35"}, {"before", "-1"}, {"after", "2"}}),
                                   MakeBlock("integrator", "x")),
                            {{"s", "x"}}, {"s.y", "x.y"}, Options(1.0, 0.005));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto events = run.EventTimes("s");
  ASSERT_EQ(events.size(), 1u);
  // CVODE locates the root of t - 0.35 to about 100 roundings of t
  EXPECT_NEAR(events[0], 0.35, 1e-13);
  EXPECT_GE(events[0], 0.35);
  const auto t = run.Time(), y = run.Column("s.y"), x = run.Column("x.y");
  for (size_t i = 0; i < t.size(); ++i) {
    EXPECT_EQ(y[i], t[i] < 0.35 ? -1.0 : 2.0) << "t = " << t[i];
    // piecewise linear: exact up to rounding and the located event time
    EXPECT_NEAR(x[i], t[i] < 0.35 ? -t[i] : -0.35 + 2 * (t[i] - 0.35), 1e-12) << "t = " << t[i];
  }
  // one step per side would do; allow CVODE's start-up steps after each (re)start
  EXPECT_LT(run.sim->stats().steps, 30);
}

TEST(SourcesTest, StepAtOrBeforeTheStartIsAlreadySwitched) {
  for (const char* time : {"0", "-1"}) {
    const auto run = Simulate(Blocks(MakeBlock("step", "s", {{"time", time}})), {}, {"s.y"}, Options(1.0, 0.1));
    ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
    for (const double y : run.Column("s.y")) EXPECT_EQ(y, 1.0) << "time = " << time;
    EXPECT_TRUE(run.EventTimes("s").empty());
  }
}

// x' = ramp(slope 2 from 0.5, initial 1): x = t until 0.5, then
// 0.5 + (t - 0.5) + (t - 0.5)^2.
TEST(SourcesTest, RampCornerIsAnEvent) {
  const auto run = Simulate(Blocks(MakeBlock("ramp", "r", {{"slope", "2"}, {"start", "0.5"}, {"initial", "1"}}),
                                   MakeBlock("integrator", "x")),
                            {{"r", "x"}}, {"r.y", "x.y"}, Options(2.0, 0.01));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto events = run.EventTimes("r");
  ASSERT_EQ(events.size(), 1u);
  EXPECT_NEAR(events[0], 0.5, 1e-13);
  const auto t = run.Time(), r = run.Column("r.y"), x = run.Column("x.y");
  for (size_t i = 0; i < t.size(); ++i) {
    const double d = t[i] - 0.5;
    EXPECT_NEAR(r[i], t[i] < 0.5 ? 1.0 : 1 + 2 * d, 1e-13) << "t = " << t[i];
    // the quadratic part starts with low-order BDF steps, each within the
    // local tolerance rtol = 1e-10 of values of order 1
    EXPECT_NEAR(x[i], t[i] < 0.5 ? t[i] : 0.5 + d + d * d, 1e-9) << "t = " << t[i];
  }
}

// Points "0 0; 1 2; 1.5 -1" from t = -0.5 to 2.5: held before 0 and after 1.5.
TEST(SourcesTest, TableInterpolatesAndHoldsBeyondTheEnds) {
  auto options = Options(2.5, 0.01);
  options.t_start = -0.5;
  const auto run = Simulate(Blocks(MakeBlock("table", "tab", {{"points", "0 0; 1 2; 1.5 -1"}})), {}, {"tab.y"},
                            options);
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto t = run.Time(), y = run.Column("tab.y");
  for (size_t i = 0; i < t.size(); ++i) {
    const double expected = t[i] <= 0 ? 0.0 : t[i] <= 1 ? 2 * t[i] : t[i] <= 1.5 ? 2 - 6 * (t[i] - 1) : -1.0;
    EXPECT_NEAR(y[i], expected, 1e-13) << "t = " << t[i];
  }
}

// A CSV table file in the test's temporary folder, removed afterwards.
class TableFileTest : public ::testing::Test {
 protected:
  void TearDown() override { std::remove(path_.c_str()); }
  const std::string& Write(const std::string& text) {
    std::ofstream(path_) << text;
    return path_;
  }
  std::string path_ = ::testing::TempDir() + "mechflow_table_" +
                      ::testing::UnitTest::GetInstance()->current_test_info()->name() + ".csv";
};

TEST_F(TableFileTest, ReadsHeaderCommentsCommasAndWhitespace) {
  const std::string& path = Write("time, force\n# measured\n0, 1\n\n1\t3  # peak\n2 ,5\n");
  const auto run = Simulate(Blocks(MakeBlock("table", "tab", {{"file", path}})), {}, {"tab.y"}, Options(3.0, 0.05));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto t = run.Time(), y = run.Column("tab.y");
  for (size_t i = 0; i < t.size(); ++i) EXPECT_NEAR(y[i], t[i] <= 2 ? 1 + 2 * t[i] : 5.0, 1e-13) << "t = " << t[i];
}

TEST_F(TableFileTest, BadRowsAreNamedByFileAndLine) {
  EXPECT_EQ(MakeError("table", {{"file", Write("t,y\n0,1\n2,5\n1,3\n")}}),
            path_ + ":4: times must increase strictly, but t = 1 follows t = 2 (line 3)");
  EXPECT_EQ(MakeError("table", {{"file", Write("0 1\n1 2\nend of data\n")}}),
            path_ + ":3: expected two numbers (t, y), found 'end of data'");
  EXPECT_EQ(MakeError("table", {{"file", Write("t y\nunits s N\n0 1\n")}}),
            path_ + ":2: expected two numbers (t, y), found 'units s N'");
  EXPECT_EQ(MakeError("table", {{"file", Write("0 1\n1 2 3\n")}}),
            path_ + ":2: expected two numbers (t, y), found 3");
  EXPECT_EQ(MakeError("table", {{"file", Write("0 1\n1 inf\n")}}), path_ + ":2: point (1, inf) is not finite");
  EXPECT_EQ(MakeError("table", {{"file", Write("t,y\n0,1\n")}}),
            path_ + ": a table needs at least two points, got 1");
  EXPECT_THAT(MakeError("table", {{"file", path_ + ".missing"}}), HasSubstr("cannot open table file"));
}

TEST(SourcesTest, BadInlineTablesAreNamedByRow) {
  EXPECT_EQ(MakeError("table", {{"points", "0 0; 1 2; 0.5 3"}}),
            "points row 3: times must increase strictly, but t = 0.5 follows t = 1 (row 2)");
  EXPECT_EQ(MakeError("table", {{"points", "0 0; 1 1; 1 2"}}),
            "points row 3: times must increase strictly, but t = 1 follows t = 1 (row 2)");
  EXPECT_EQ(MakeError("table", {{"points", "0 0; 1 2 3"}}), "points row 2 has 3 numbers; expected two (t y)");
  EXPECT_EQ(MakeError("table", {{"points", "0 0"}}), "points: a table needs at least two points, got 1");
  EXPECT_EQ(MakeError("table"), "give either 'points' or 'file', not both or neither");
}

TEST(SourcesTest, FactoriesRejectUnusableParameters) {
  EXPECT_EQ(MakeError("step", {{"time", "inf"}}), "'time' must be a finite number, got inf");
  EXPECT_EQ(MakeError("sine", {{"frequency", "nan"}}), "'frequency' must be a finite number, got nan");
  EXPECT_EQ(MakeError("constant", {{"value", "1 inf"}}), "'value' must hold finite numbers, got inf");
}

TEST(SourcesTest, SourcesHaveNoInputs) {
  for (const char* type : {"clock", "step", "ramp", "sine"}) {
    const auto b = MakeBlock(type, "b");
    EXPECT_EQ(b->num_inputs(), 0) << type;
    EXPECT_EQ(b->num_outputs(), 1) << type;
    EXPECT_EQ(b->output_port(0).name, "y") << type;
  }
  EXPECT_EQ(MakeBlock("constant", "c", {{"value", Num(0.1) + " 2 3"}})->output_port(0).width, 3);
}

}  // namespace
}  // namespace mechflow::blocks
