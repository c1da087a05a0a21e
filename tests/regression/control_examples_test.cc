// Examples driven by control scripts: Molecule (docs/ELEMENTS.md 9.15,
// test MO-1) and the inverted pendulum under sampled PD control in Lua,
// against the formula and against the sampled closed loop integrated here.

#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "diagrams/xml_reader.h"
#include "tests/test_util.h"

namespace mechflow {
namespace {

const std::string kExamples = std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/";

using testing::RunDescription;

TEST(ControlExamplesTest, MoleculeDegreeFollowsTheFormulaAtEveryOutputTime) {
  diagrams::DiagramDescription d = diagrams::ReadDiagramFile(kExamples + "molecule.xml");
  // rows at k pi/100, so that t = pi/10 (MO-1) is one of them
  for (auto& a : d.output)
    if (a.name == "interval") a.value = "pi/100";
  const auto run = RunDescription(std::move(d));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto t = run.Column("time"), mdeg = run.Column("mdeg"), diagonal = run.Column("diagonal distance");
  const double nmin = 1.2, nmax = 5, om = 5;
  ASSERT_GT(t.size(), 60u);
  for (std::size_t i = 0; i < t.size(); ++i) {
    EXPECT_NEAR(mdeg[i], (nmax + nmin) / 2 + (nmax - nmin) / 2 * std::sin(om * t[i]), 1e-12) << "t = " << t[i];
    // the expression block reads mdeg directly and follows every change
    EXPECT_NEAR(diagonal[i], std::pow(3.0, 1 - mdeg[i] / 2), 1e-12) << "t = " << t[i];
  }
  EXPECT_EQ(mdeg[0], 3.1);                    // MO-1: mdeg(0)
  EXPECT_NEAR(t[10], M_PI / 10, 1e-15);
  EXPECT_NEAR(mdeg[10], 5.0, 1e-12);          // MO-1: mdeg(pi/10)
  EXPECT_EQ(run.loaded.control->changes().size(), t.size());
}

// I phi'' = m g (l/2) sin(phi) + tau + dist exp(-((t - t_dist)/0.03)^2),
// tau held between samples at -kp phi_k - kd omega_k: classic RK4 with steps
// that divide the sampling period.
struct SampledPendulum {
  double m = 1, l = 1, g = 9.81, dist = 5, t_dist = 2, period = 0.01;
  double I() const { return m * l * l / 3; }
  double kp() const { return m * 9.81 * l / 2 + I() * 4 * M_PI * M_PI; }
  double kd() const { return 2 * 0.7 * 2 * M_PI * I(); }
  double Acceleration(double t, double phi, double tau) const {
    const double pulse = dist * std::exp(-std::pow((t - t_dist) / 0.03, 2));
    return (m * g * l / 2 * std::sin(phi) + tau + pulse) / I();
  }
};

TEST(ControlExamplesTest, PdControlInLuaMatchesTheSampledClosedLoopAndHoldsThePendulumUp) {
  const auto run = RunDescription(diagrams::ReadDiagramFile(kExamples + "pendulum_pd_control.xml"));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto t = run.Column("time"), phi = run.Column("tilt"), torque = run.Column("controller torque");

  const SampledPendulum p;
  const int substeps = 20;  // RK4 steps per sample; the rows (every 5 ms) fall on them
  const double h = p.period / substeps;
  double x = 0.1, v = 0.0, worst = 0.0, largest_after = 0.0;
  std::size_t row = 0;
  for (long k = 0; row < t.size(); ++k) {
    const double tau = -p.kp() * x - p.kd() * v;  // sampled at k period, then held
    for (int j = 0; j < substeps; ++j) {
      const double ts = k * p.period + j * h;
      if (row < t.size() && std::abs(t[row] - ts) < 1e-9) {
        worst = std::max(worst, std::abs(phi[row] - x));
        EXPECT_NEAR(torque[row], tau, 5e-6) << "t = " << ts;  // N m: kp and kd times the state errors
        if (ts > p.t_dist) largest_after = std::max(largest_after, std::abs(phi[row]));
        ++row;
      }
      auto f = [&](double tf, double xf) { return p.Acceleration(tf, xf, tau); };
      const double k1x = v, k1v = f(ts, x);
      const double k2x = v + h / 2 * k1v, k2v = f(ts + h / 2, x + h / 2 * k1x);
      const double k3x = v + h / 2 * k2v, k3v = f(ts + h / 2, x + h / 2 * k2x);
      const double k4x = v + h * k3v, k4v = f(ts + h, x + h * k3x);
      x += h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
      v += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
    }
  }
  std::printf("largest tilt difference %.3g rad, largest tilt after the pulse %.4f rad\n", worst, largest_after);
  EXPECT_LT(worst, 1e-6);  // rad, against the reference over all 5 s
  // the disturbance tilts it by less than 0.07 rad, and it is back upright
  EXPECT_LT(largest_after, 0.07);
  EXPECT_GT(largest_after, 0.03);  // the pulse did knock it
  EXPECT_LT(std::abs(phi.back()), 1e-4);
}

TEST(ControlExamplesTest, ScriptChangeReachesAMechanismForceLawAsALoadTimeValueWould) {
  // DampingRatio's spring law is a Lua expression of cstiff and cdiss, both
  // defined from f: a script that sets f = 2 in init must give the run that
  // --set f=2 gives; the box's mass (a fixed use of `mass`) stays as loaded
  diagrams::DiagramDescription scripted = diagrams::ReadDiagramFile(kExamples + "damping_ratio.xml");
  scripted.script = {"function init(sim) sim:set('f', 2) end", "=test", {}};
  const auto by_script = RunDescription(std::move(scripted));
  ASSERT_TRUE(by_script.outcome.ok) << by_script.outcome.failure;

  diagrams::LoadOptions options;
  options.overrides = {{"f", 2.0}};
  const auto by_set = RunDescription(diagrams::ReadDiagramFile(kExamples + "damping_ratio.xml"), options);
  ASSERT_TRUE(by_set.outcome.ok);

  const auto a = by_script.Column("m.z"), b = by_set.Column("m.z");
  ASSERT_EQ(a.size(), b.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(a[i] - b[i]));
  EXPECT_LT(worst, 1e-12);

  diagrams::DiagramDescription heavier = diagrams::ReadDiagramFile(kExamples + "damping_ratio.xml");
  heavier.script = {"function init(sim) sim:set('mass', 2000) end", "=test", {}};
  const auto refused = RunDescription(std::move(heavier));
  ASSERT_FALSE(refused.outcome.ok);
  EXPECT_NE(refused.outcome.failure.find("identifier 'mass' cannot change during a run"), std::string::npos)
      << refused.outcome.failure;
}

}  // namespace
}  // namespace mechflow
