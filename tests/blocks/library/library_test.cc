// The standard blocks, each in a tiny diagram with a hand-computable answer.

#include <cmath>
#include <cstdio>
#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mech/friction_law.h"
#include "tests/numbers.h"
#include "tests/test_util.h"

namespace mechflow::blocks::library_test {  // names of its own: the files of its folder are compiled together
namespace {

using ::testing::HasSubstr;
using mechflow::testing::InputErrorOf;
using mechflow::testing::LoadXml;
using mechflow::testing::RunXml;

using mechflow::testing::kPi;

// A diagram with the given blocks, connections and logs; t in [0, t_end].
std::string Diagram(const std::string& blocks, const std::string& connections, const std::string& logs,
                    double t_end = 2.0, double interval = 0.01) {
  return "<diagram name='t'><blocks>" + blocks + "</blocks><connections>" + connections +
         "</connections><solver t_end='" + std::to_string(t_end) +
         "' rtol='1e-10' atol='1e-12'/><output interval='" + std::to_string(interval) + "'>" + logs +
         "</output></diagram>";
}

TEST(LibraryTest, SourcesGiveTheirFormulas) {
  const auto run = RunXml(Diagram(
      "<block type='constant' name='c' value='1.5 -2'/><block type='clock' name='clk'/>"
      "<block type='ramp' name='r' slope='2' start='0.5' initial='1'/>"
      "<block type='sine' name='s' amplitude='3' frequency='0.5' phase='0.25' bias='1'/>"
      "<block type='table' name='tab' points='0 0; 1 2; 1.5 -1'/>",
      "", "<log signal='c.y' label='c'/><log signal='clk.y' label='clk'/><log signal='r.y' label='r'/>"
          "<log signal='s.y' label='s'/><log signal='tab.y' label='tab'/>"));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto t = run.Column("time");
  const auto c0 = run.Column("c[0]"), c1 = run.Column("c[1]"), clk = run.Column("clk"), r = run.Column("r"),
             s = run.Column("s"), tab = run.Column("tab");
  for (size_t i = 0; i < t.size(); ++i) {
    EXPECT_EQ(c0[i], 1.5);
    EXPECT_EQ(c1[i], -2.0);
    EXPECT_NEAR(clk[i], t[i], 1e-12);
    EXPECT_NEAR(r[i], t[i] < 0.5 ? 1.0 : 1.0 + 2.0 * (t[i] - 0.5), 1e-9);
    EXPECT_NEAR(s[i], 1 + 3 * std::sin(2 * kPi * 0.5 * t[i] + 0.25), 1e-12);
    const double expected = t[i] <= 1 ? 2 * t[i] : t[i] <= 1.5 ? 2 - 6 * (t[i] - 1) : -1.0;
    EXPECT_NEAR(tab[i], expected, 1e-9) << "t = " << t[i];
  }
}

TEST(LibraryTest, StepIsAnEventAndIntegratesExactly) {
  // x' = step(0.35, 0 -> 2): x = 2 (t - 0.35) after the step
  const auto run = RunXml(Diagram("<block type='step' name='s' time='0.35' after='2'/>"
                                  "<block type='integrator' name='x'/>",
                                  "<connect from='s.y' to='x.u'/>", "<log signal='x.y' label='x'/>", 1.0));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  ASSERT_EQ(run.sim->events().size(), 1u);
  EXPECT_NEAR(run.sim->events()[0].time, 0.35, 1e-12);
  const auto t = run.Column("time"), x = run.Column("x");
  for (size_t i = 0; i < t.size(); ++i) EXPECT_NEAR(x[i], t[i] < 0.35 ? 0.0 : 2 * (t[i] - 0.35), 1e-9);
  // a constant derivative on each side of a located event needs only a few steps
  EXPECT_LT(run.sim->stats().steps, 40);
}

TEST(LibraryTest, IntegratorStopsAtItsLimitAndLeavesWhenTheInputTurns) {
  // x' = cos t, x(0) = 0, upper = 0.5: x = sin t until t = pi/6, then held at
  // 0.5 until cos t < 0 at t = pi/2, then x = 0.5 + (sin t - 1).
  const auto run = RunXml(Diagram("<block type='sine' name='u' phase='pi/2' frequency='1/(2*pi)'/>"
                                  "<block type='integrator' name='x' upper='0.5' lower='-0.2'/>",
                                  "<connect from='u.y' to='x.u'/>", "<log signal='x.y' label='x'/>", 3.0));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto& events = run.sim->events();
  ASSERT_GE(events.size(), 3u);
  EXPECT_NEAR(events[0].time, kPi / 6, 1e-8);
  EXPECT_NEAR(events[1].time, kPi / 2, 1e-8);
  // x = sin t - 0.5 reaches the lower limit -0.2 at asin(0.3) past pi/2
  EXPECT_NEAR(events[2].time, kPi - std::asin(0.3), 1e-8);
  const auto t = run.Column("time"), x = run.Column("x");
  for (size_t i = 0; i < t.size(); ++i) {
    double expected = std::sin(t[i]);
    if (t[i] > kPi / 6) expected = 0.5;
    if (t[i] > kPi / 2) expected = std::sin(t[i]) - 0.5;
    if (t[i] > kPi - std::asin(0.3)) expected = -0.2;
    EXPECT_NEAR(x[i], expected, 1e-7) << "t = " << t[i];
  }
}

TEST(LibraryTest, CornersFollowTheirClosedForms) {
  const auto run = RunXml(Diagram("<block type='sine' name='u' amplitude='2'/>"
                                  "<block type='abs' name='a'/>"
                                  "<block type='saturation' name='sat' lower='-1' upper='1.5'/>"
                                  "<block type='dead_zone' name='dz' start='-0.5' end='0.5'/>",
                                  "<connect from='u.y' to='a.u'/><connect from='u.y' to='sat.u'/>"
                                  "<connect from='u.y' to='dz.u'/>",
                                  "<log signal='a.y' label='a'/><log signal='sat.y' label='sat'/>"
                                  "<log signal='dz.y' label='dz'/>"));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto t = run.Column("time"), a = run.Column("a"), sat = run.Column("sat"), dz = run.Column("dz");
  for (size_t i = 0; i < t.size(); ++i) {
    const double u = 2 * std::sin(2 * kPi * t[i]);
    EXPECT_NEAR(a[i], std::abs(u), 1e-9);
    EXPECT_NEAR(sat[i], std::clamp(u, -1.0, 1.5), 1e-9);
    EXPECT_NEAR(dz[i], u < -0.5 ? u + 0.5 : u > 0.5 ? u - 0.5 : 0.0, 1e-9);
  }
  // every corner crossing was an event: over two periods abs crosses 0 four
  // times (t = 0.5, 1, 1.5, 2 minus the start), saturation and dead zone 8 each
  EXPECT_GE(run.sim->stats().events, 18);
}

TEST(LibraryTest, ArithmeticBlocks) {
  const auto run = RunXml(Diagram("<block type='constant' name='a' value='3'/><block type='constant' name='b' value='4'/>"
                                  "<block type='gain' name='g' k='-2.5'/><block type='sum' name='s' signs='+-+'/>"
                                  "<block type='product' name='p' operations='**/'/>",
                                  "<connect from='a' to='g'/><connect from='a' to='s.u1'/><connect from='b' to='s.u2'/>"
                                  "<connect from='g' to='s.u3'/><connect from='a' to='p.u1'/><connect from='b' to='p.u2'/>"
                                  "<connect from='g' to='p.u3'/>",
                                  "<log signal='g'/><log signal='s'/><log signal='p'/>", 0.1));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  EXPECT_DOUBLE_EQ(run.Column("g.y").back(), -7.5);
  EXPECT_DOUBLE_EQ(run.Column("s.y").back(), 3 - 4 - 7.5);
  EXPECT_DOUBLE_EQ(run.Column("p.y").back(), 3 * 4 / -7.5);
}

TEST(LibraryTest, ProductDivisionByZeroFailsTheRunWithTheBlockNamed) {
  const auto run = RunXml(Diagram("<block type='constant' name='one' value='1'/><block type='constant' name='r' value='0'/>"
                                  "<block type='product' name='q' operations='*/'/><block type='integrator' name='x'/>",
                                  "<connect from='one' to='q.u1'/><connect from='r' to='q.u2'/><connect from='q' to='x'/>",
                                  "<log signal='x.y'/>", 2.0));
  EXPECT_FALSE(run.outcome.ok);
  EXPECT_THAT(run.outcome.failure, HasSubstr("block 'q': division by zero"));
}

TEST(LibraryTest, FirstOrderLagStepResponse) {
  const auto run = RunXml(Diagram("<block type='step' name='s' time='0'/>"
                                  "<block type='first_order_lag' name='lag' time_constant='0.3' gain='2'/>",
                                  "<connect from='s' to='lag'/>", "<log signal='lag.y' label='y'/>"));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto t = run.Column("time"), y = run.Column("y");
  for (size_t i = 0; i < t.size(); ++i) EXPECT_NEAR(y[i], 2 * (1 - std::exp(-t[i] / 0.3)), 1e-8);
}

TEST(LibraryTest, FrictionFromNormalForceFollowsItsLaw) {
  // N and v as ramps; the law written out independently here
  const auto run = RunXml(Diagram("<block type='ramp' name='N' slope='10' initial='-1'/>"
                                  "<block type='sine' name='v' amplitude='0.05'/>"
                                  "<block type='friction_from_normal_force' name='f' mu_static='0.6' mu_dynamic='0.4' "
                                  "stribeck_velocity='0.01' viscous='2' regularisation_velocity='1e-3'/>",
                                  "<connect from='N' to='f.N'/><connect from='v' to='f.v'/>",
                                  "<log signal='f.F' label='F'/>"));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto t = run.Column("time"), F = run.Column("F");
  for (size_t i = 0; i < t.size(); ++i) {
    const double n = std::max(0.0, -1 + 10 * t[i]);
    const double v = 0.05 * std::sin(2 * kPi * t[i]);
    const double mu = 0.4 + 0.2 * std::exp(-(v / 0.01) * (v / 0.01));
    const double expected = -(mu * n * std::tanh(v / 1e-3) + 2 * v);
    EXPECT_NEAR(F[i], expected, 1e-12);
    if (v != 0) {
      EXPECT_LE(F[i] * v, 0.0) << "friction must oppose sliding";
    }
  }
}

TEST(LibraryTest, SampleHoldUpdatesExactlyAtItsSampleTimes) {
  const auto run = RunXml(Diagram("<block type='clock' name='clk'/>"
                                  "<block type='sample_hold' name='h' period='0.1' offset='0.05' initial='-1'/>",
                                  "<connect from='clk' to='h'/>", "<log signal='h.y' label='held'/>", 1.0));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto t = run.Column("time"), held = run.Column("held");
  for (size_t i = 0; i < t.size(); ++i) {
    // the last sample time at or before t (output rows are taken after the hit)
    const double k = std::floor((t[i] - 0.05) / 0.1 + 1e-9);
    const double expected = t[i] < 0.05 - 1e-12 ? -1.0 : 0.05 + 0.1 * k;
    // a row at a sample time shows the value after the hit
    EXPECT_NEAR(held[i], expected, 1e-12) << "t = " << t[i];
  }
  EXPECT_EQ(run.sim->stats().sample_hits, 10);
}

TEST(LibraryTest, TableFromCsvFile) {
  const std::string path = ::testing::TempDir() + "/mechflow_table.csv";
  {
    std::ofstream f(path);
    f << "time,value\n0, 1\n# a comment\n2, 5\n";
  }
  const std::string xml = Diagram("<block type='table' name='tab' file='" + path + "'/>", "",
                                  "<log signal='tab.y' label='y'/>");
  diagrams::LoadOptions options;  // the file is outside test.xml's folder
  options.allow_read = {::testing::TempDir()};
  const auto run = RunXml(xml, options);
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto t = run.Column("time"), y = run.Column("y");
  for (size_t i = 0; i < t.size(); ++i) EXPECT_NEAR(y[i], 1 + 2 * t[i], 1e-12);

  {
    std::ofstream f(path);
    f << "0 1\n2 5\n1 3\n";
  }
  EXPECT_THAT(InputErrorOf([&] { LoadXml(xml, options); }),
              HasSubstr("mechflow_table.csv:3: times must increase strictly"));
  std::remove(path.c_str());
}

TEST(LibraryTest, FactoriesRejectUnusableParameters) {
  auto error = [](const std::string& block) {
    return InputErrorOf([&] { LoadXml(Diagram(block, "", "")); });
  };
  EXPECT_THAT(error("<block type='saturation' name='s' lower='1' upper='0'/>"),
              HasSubstr("block 's' (saturation): 'lower' must be less than 'upper'"));
  EXPECT_THAT(error("<block type='sum' name='s' signs='+*'/>"), HasSubstr("'signs' may contain only"));
  EXPECT_THAT(error("<block type='table' name='t' points='0 1; 0 2'/>"), HasSubstr("times must increase strictly"));
  EXPECT_THAT(error("<block type='table' name='t'/>"), HasSubstr("give either 'points' or 'file'"));
  EXPECT_THAT(error("<block type='integrator' name='x' reset='up'/>"),
              HasSubstr("'reset' must be rising, falling or either"));
  EXPECT_THAT(error("<block type='first_order_lag' name='l' time_constant='0'/>"),
              HasSubstr("'time_constant' must be > 0"));
  EXPECT_THAT(error("<block type='friction_from_normal_force' name='f' mu_static='0.5' mu_dynamic='0.3' "
                    "regularisation_velocity='0'/>"),
              HasSubstr("regularisation_velocity must be > 0"));
  EXPECT_THAT(error("<block type='sample_hold' name='h' period='-1'/>"), HasSubstr("'period' must be > 0"));
  EXPECT_THAT(error("<block type='gain' name='g' k='1' width='1.5'/>"), HasSubstr("'width' must be a whole number"));
}

}  // namespace
}  // namespace mechflow::blocks::library_test
