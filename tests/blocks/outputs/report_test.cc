// Reports (blocks/outputs/report.h): extrema located by the integrator on its dense
// output, against closed forms, far finer than the output interval; a run
// with reports (one step at a time) gives the rows and events of a run
// without.

#include "blocks/outputs/report.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "blocks/framework/diagram_builder.h"
#include "blocks/library/sine.h"
#include "blocks/solver/simulator.h"
#include "tests/test_util.h"

namespace mechflow::blocks {
namespace {

// x'' + 2 zeta w x' + w^2 x = 0 from x = 0, x' = 1 (test-local block, output x).
class DampedOscillator : public Block {
 public:
  DampedOscillator(std::string name, double w, double zeta) : Block("oscillator", name), w_(w), zeta_(zeta) {
    DeclareOutputPort("x");
    DeclareContinuousStates(2);
  }

 protected:
  void DoInitialize(const BlockContext& ctx) const override {
    ctx.state()[0] = 0.0;
    ctx.state()[1] = 1.0;
  }
  void DoCalcOutput(int, const BlockContext& ctx) const override { ctx.output(0)[0] = ctx.state()[0]; }
  void DoCalcDerivatives(const BlockContext& ctx) const override {
    const auto x = ctx.state();
    ctx.derivative()[0] = x[1];
    ctx.derivative()[1] = -2 * zeta_ * w_ * x[1] - w_ * w_ * x[0];
  }

 private:
  double w_, zeta_;
};

TEST(ReportTest, FirstMaximumAndMinimumOfADampedOscillatorToClosedForm) {
  const double w = 2 * M_PI, zeta = 0.1, wd = w * std::sqrt(1 - zeta * zeta);
  DiagramBuilder builder;
  builder.AddBlock(std::make_unique<DampedOscillator>("osc", w, zeta));
  auto diagram = builder.Build();
  SolverOptions options;
  options.t_end = 1.0;  // one damped period (1.005 s) minus a little: one maximum, one minimum
  options.rtol = 1e-10;
  options.atol = 1e-12;
  options.output_interval = 0.1;
  Simulator sim(*diagram, options, {diagram->ResolveSignal("osc.x")});
  const SignalRef x = diagram->ResolveSignal("osc.x");
  sim.SetReports({{"max", "m", ReportKind::kPeak, x},
                  {"min", "m", ReportKind::kMin, x},
                  {"magnitude", "m", ReportKind::kPeakAbs, x}});
  ASSERT_TRUE(sim.Run().ok);
  // x = exp(-zeta w t) sin(wd t) / wd: x' = 0 where tan(wd t) = wd / (zeta w),
  // t_max = acos(zeta) / wd, and the minimum half a damped period later
  const double t_max = std::acos(zeta) / wd, t_min = t_max + M_PI / wd;
  auto x_at = [&](double t) { return std::exp(-zeta * w * t) * std::sin(wd * t) / wd; };
  const auto& f = sim.results().figures();
  ASSERT_EQ(f.size(), 3u);
  for (const auto& figure : f) EXPECT_TRUE(figure.found) << figure.label;
  // the value to the solver's accuracy (rtol 1e-10 on x ~ 0.13); the time of
  // a smooth extremum to about sqrt(value accuracy / curvature): 1e-6 s,
  // 1e5 times finer than the output interval of 0.1 s
  EXPECT_NEAR(f[0].value, x_at(t_max), 1e-9);
  EXPECT_NEAR(f[0].time, t_max, 1e-6);
  EXPECT_NEAR(f[1].value, x_at(t_min), 1e-9);
  EXPECT_NEAR(f[1].time, t_min, 1e-6);
  EXPECT_NEAR(f[2].value, x_at(t_max), 1e-9);
  EXPECT_NEAR(f[2].time, t_max, 1e-6);
  EXPECT_EQ(f[0].signal, "osc.x");
  EXPECT_EQ(f[1].kind, ReportKind::kMin);
  // the output grid alone would be off by up to half an interval
  const auto grid = sim.results().Column(1);
  EXPECT_LT(*std::max_element(grid.begin(), grid.end()), f[0].value);
}

TEST(ReportTest, ExtremaAtEventsTakeEachSideAndRowsMatchARunWithoutReports) {
  const std::string path = std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/bouncing_ball_blocks.xml";
  const auto loaded = diagrams::LoadDiagram(path, {});
  Simulator plain(*loaded.diagram, loaded.solver, loaded.logged);
  ASSERT_TRUE(plain.Run().ok);
  const SignalRef v = loaded.diagram->ResolveSignal("v.y");
  Simulator watched(*loaded.diagram, loaded.solver, loaded.logged);
  watched.SetReports({{"fastest fall", "m/s", ReportKind::kMin, v}, {"fastest rise", "m/s", ReportKind::kPeak, v}});
  ASSERT_TRUE(watched.Run().ok);
  // the same trajectory: rows on the same grid, events at the same instants
  const Results& a = plain.results();
  const Results& b = watched.results();
  ASSERT_EQ(a.num_rows(), b.num_rows());
  for (int i = 0; i < a.num_rows(); ++i)
    for (int c = 0; c < a.num_columns(); ++c) ASSERT_NEAR(a.at(i, c), b.at(i, c), 1e-8) << "row " << i << " col " << c;
  ASSERT_EQ(plain.events().size(), watched.events().size());
  for (std::size_t i = 0; i < plain.events().size(); ++i)
    EXPECT_NEAR(plain.events()[i].time, watched.events()[i].time, 1e-9);
  // v reaches -sqrt(2 g h0) just before the first impact at t1 = sqrt(2 h0 / g)
  // and +e sqrt(2 g h0) just after it: the extremum on each side of the event
  const double g = 9.81, h0 = 10, e = 0.8, t1 = std::sqrt(2 * h0 / g), v1 = std::sqrt(2 * g * h0);
  const auto& f = watched.results().figures();
  EXPECT_NEAR(f[0].value, -v1, 1e-7);
  EXPECT_NEAR(f[0].time, t1, 1e-8);
  EXPECT_NEAR(f[1].value, e * v1, 1e-7);
  EXPECT_NEAR(f[1].time, t1, 1e-8);
}

TEST(ReportTest, AFailedRunReportsWhatItFoundUpToTheFailure) {
  // x' = x^2 from 1 blows up at t = 1: the run fails there; the largest value
  // seen is far above the output rows' and no later than the failure
  const std::string xml =
      "<diagram><blocks><block type='integrator' name='x' initial='1'/>"
      "<block type='product' name='sq' inputs='2'/></blocks>"
      "<connections><connect from='x.y' to='sq.u1'/><connect from='x.y' to='sq.u2'/>"
      "<connect from='sq.y' to='x.u'/></connections>"
      "<solver t_end='2' rtol='1e-8' atol='1e-10'/>"
      "<output interval='0.1'><log signal='x.y'/><report peak='x.y' label='largest x'/></output></diagram>";
  const auto run = mechflow::testing::RunXml(xml);
  ASSERT_FALSE(run.outcome.ok);
  const auto& f = run.sim->results().figures();
  ASSERT_EQ(f.size(), 1u);
  EXPECT_TRUE(f[0].found);
  EXPECT_EQ(f[0].label, "largest x");
  EXPECT_GT(f[0].value, 1e3);  // the rows stop at t = 0.9, x = 10
  EXPECT_LE(f[0].time, run.outcome.t_reached + 1e-12);
  EXPECT_GT(f[0].time, 0.999);  // x = 1/(1 - t) > 1e3
}

// The figures over a run (what a report prints must be right, not just plausible) against closed forms of
// x = sin(w t) / w (undamped) and of the damped oscillator's zero crossings.
TEST(ReportTest, MeanRmsIntegralFinalCrossingAndPeriodToClosedForms) {
  const double w = 2 * M_PI * 1.3, T = 2.7;
  DiagramBuilder builder;
  builder.AddBlock(std::make_unique<DampedOscillator>("osc", w, 0.0));
  auto diagram = builder.Build();
  SolverOptions options;
  options.t_end = T;
  options.rtol = 1e-10;
  options.atol = 1e-12;
  options.output_interval = 0.1;  // far coarser than what the figures resolve
  Simulator sim(*diagram, options, {diagram->ResolveSignal("osc.x")});
  const SignalRef x = diagram->ResolveSignal("osc.x");
  ReportRequest crossing{"half", "", ReportKind::kCrossing, x};
  crossing.level = 0.5 / w;
  sim.SetReports({{"mean", "", ReportKind::kMean, x}, {"rms", "", ReportKind::kRms, x},
                  {"integral", "", ReportKind::kIntegral, x}, {"final", "", ReportKind::kFinal, x}, crossing,
                  {"period", "", ReportKind::kPeriod, x}});
  ASSERT_TRUE(sim.Run().ok);
  const auto& f = sim.results().figures();
  ASSERT_EQ(f.size(), 6u);
  for (const auto& figure : f) EXPECT_TRUE(figure.found) << figure.label;
  const double integral = (1 - std::cos(w * T)) / (w * w);
  const double square = (T / 2 - std::sin(2 * w * T) / (4 * w)) / (w * w);
  EXPECT_NEAR(f[0].value, integral / T, 1e-9);
  EXPECT_NEAR(f[1].value, std::sqrt(square / T), 1e-9);
  EXPECT_NEAR(f[2].value, integral, 1e-9);
  EXPECT_NEAR(f[2].time, T, 1e-12);
  EXPECT_NEAR(f[3].value, std::sin(w * T) / w, 1e-10);
  EXPECT_NEAR(f[4].time, std::asin(0.5) / w, 1e-9);  // sin(w t) = 1/2 first
  EXPECT_NEAR(f[5].value, 2 * M_PI / w, 1e-9);       // upward zeros one period apart
}

TEST(ReportTest, PeriodOfADampedOscillationAndALevelNeverReached) {
  const double w = 2 * M_PI, zeta = 0.05, wd = w * std::sqrt(1 - zeta * zeta);
  DiagramBuilder builder;
  builder.AddBlock(std::make_unique<DampedOscillator>("osc", w, zeta));
  auto diagram = builder.Build();
  SolverOptions options;
  options.t_end = 6.3;
  options.rtol = 1e-10;
  options.atol = 1e-12;
  Simulator sim(*diagram, options, {diagram->ResolveSignal("osc.x")});
  const SignalRef x = diagram->ResolveSignal("osc.x");
  ReportRequest never{"never", "", ReportKind::kCrossing, x};
  never.level = 1.0;  // x never exceeds 1 / w
  sim.SetReports({{"period", "", ReportKind::kPeriod, x}, never});
  ASSERT_TRUE(sim.Run().ok);
  const auto& f = sim.results().figures();
  EXPECT_NEAR(f[0].value, 2 * M_PI / wd, 1e-9);
  EXPECT_FALSE(f[1].found);
}

// A sine that no state depends on: the integrator's steps do not follow it
// (they are as long as the output interval allows), so the reports look at
// least sixteen times a period (Block::OwnTimeScale); the figures are the
// closed form's whatever the interval.
TEST(ReportTest, ASourceNoStateFollowsIsWatchedOnItsOwnTimeScale) {
  DiagramBuilder builder;
  builder.AddBlock(std::make_unique<SineBlock>("s", 1.0, 1.0, 0.0, 0.0));  // sin(2 pi t)
  auto diagram = builder.Build();
  for (const double interval : {0.01, 0.5, 2.0}) {
    SolverOptions options;
    options.t_end = 10.0;
    options.output_interval = interval;
    Simulator sim(*diagram, options, {diagram->ResolveSignal("s.y")});
    const SignalRef y = diagram->ResolveSignal("s.y");
    ReportRequest crossing{"half", "", ReportKind::kCrossing, y};
    crossing.level = 0.5;
    sim.SetReports({{"period", "", ReportKind::kPeriod, y}, {"rms", "", ReportKind::kRms, y},
                    {"mean", "", ReportKind::kMean, y}, {"peak", "", ReportKind::kPeak, y}, crossing});
    ASSERT_TRUE(sim.Run().ok);
    const auto& f = sim.results().figures();
    EXPECT_NEAR(f[0].value, 1.0, 1e-9) << "interval " << interval;
    EXPECT_NEAR(f[1].value, std::sqrt(0.5), 1e-9) << "interval " << interval;
    EXPECT_NEAR(f[2].value, 0.0, 1e-9) << "interval " << interval;
    EXPECT_NEAR(f[3].time, 0.25, 1e-6) << "interval " << interval;
    EXPECT_NEAR(f[4].time, 1.0 / 12.0, 1e-9) << "interval " << interval;
  }
}

}  // namespace
}  // namespace mechflow::blocks
