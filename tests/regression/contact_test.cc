// Points-plane contact (ELEMENTS.md 5.1, test CT-1): a unit mass dropped at
// 1 m/s on a linear spring-damper contact rebounds with the restitution of
// the clipped law (the force never pulls), computed independently in the
// ELEMENTS.md table.

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "blocks/simulator.h"
#include "diagrams/loader.h"
#include "tests/test_util.h"

namespace mechflow {
namespace {

std::string Drop(double beta) {
  return "<diagram>\n<identifiers><identifier name=\"beta\" value=\"" + std::to_string(beta) +
         "\"/></identifiers>\n"
         "<mechanism name=\"m\" gravity=\"0 0 0\">\n"
         "<body name=\"Ball\" mass=\"1\" inertia=\"0.1 0.1 0.1\"/>\n"
         "<joint name=\"z\" type=\"translational\" body1=\"Base0\" body2=\"Ball\" axis=\"0 0 1\" q0=\"0.01\" v0=\"-1\"/>\n"
         "<contact name=\"floor\" type=\"points_plane\" body1=\"Ball\" points=\"0 0 0\" body2=\"Base0\" normal=\"0 0 1\"\n"
         "         stiffness=\"1e4\" damping=\"2*beta*sqrt(1e4)\"/>\n"
         "<sensor name=\"v\" kind=\"velocity\" dof=\"z\"/>\n"
         "<sensor name=\"n\" kind=\"element\" element=\"floor\" quantity=\"normal\"/>\n"
         "</mechanism>\n<solver t_end=\"0.1\" rtol=\"1e-9\" atol=\"1e-12\"/>\n"
         "<output interval=\"0.0001\"><log signal=\"m.v\"/><log signal=\"m.n\"/></output>\n</diagram>\n";
}

TEST(ContactTest, ReboundOfTheClippedLinearLawCT1) {
  const double beta[4] = {0.05, 0.1, 0.2, 0.3};
  const double restitution[4] = {0.8588, 0.7441, 0.5717, 0.4510};  // ELEMENTS.md 5.1, clipped
  for (int k = 0; k < 4; ++k) {
    const auto run = testing::RunXml(Drop(beta[k]));
    ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
    const auto v = run.Column("m.v"), n = run.Column("m.n");
    EXPECT_NEAR(v.back(), restitution[k], 5e-4) << "beta " << beta[k];
    EXPECT_GE(*std::min_element(n.begin(), n.end()), 0.0) << "the contact must never pull";
    // touching and leaving are events
    EXPECT_EQ(run.sim->events().size(), 2u);
  }
}

TEST(ContactTest, OscillationsSelfExcitedStickSlipCT4) {
  diagrams::LoadOptions options;
  const auto loaded =
      diagrams::LoadDiagram(std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/oscillations.xml", options);
  blocks::Simulator sim(*loaded.diagram, loaded.solver, loaded.logged);
  ASSERT_TRUE(sim.Run().ok);
  const auto& r = sim.results();
  const auto t = r.Column(0), v = r.Column(r.FindColumn("m.v")), f = r.Column(r.FindColumn("m.spring_force"));
  // initial stick: until the spring pulls mu m g = 2.943 N, at 0.2943 s
  // (the body creeps at about v_eps meanwhile: regularised friction)
  std::size_t start = 0;
  while (-f[start] < 2.94) ++start;
  EXPECT_NEAR(t[start], 0.2943, 2e-3);
  EXPECT_LT(v[start], 3e-4);  // creep of the regularised law (v_eps = 1e-5) near the limit
  // then velocity peaks 2 v_leader, one period 2 pi sqrt(m/k) apart
  std::vector<double> peaks;
  for (std::size_t i = start + 1; i + 1 < t.size(); ++i)
    if (v[i] > v[i - 1] && v[i] >= v[i + 1] && v[i] > 0.1) peaks.push_back(t[i]);
  ASSERT_GE(peaks.size(), 5u);
  EXPECT_NEAR((peaks.back() - peaks.front()) / (peaks.size() - 1), 2 * M_PI * std::sqrt(1.0 / 100.0), 2e-3);
  double vmax = 0, fmax = 0;
  for (std::size_t i = start; i < t.size(); ++i) vmax = std::max(vmax, v[i]), fmax = std::max(fmax, -f[i]);
  EXPECT_NEAR(vmax, 0.2, 2e-3);
  EXPECT_NEAR(fmax, 3.943, 5e-3);
}

TEST(ContactTest, FallingCubeSlidesDownTheInclineAndStopsCT2) {
  const auto loaded =
      diagrams::LoadDiagram(std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/falling.xml", {});
  blocks::Simulator sim(*loaded.diagram, loaded.solver, loaded.logged);
  const auto outcome = sim.Run();
  ASSERT_TRUE(outcome.ok) << outcome.failure;
  const auto& r = sim.results();
  auto column = [&](const std::string& name) { return r.Column(r.FindColumn(name)); };
  const auto t = column("time"), vy = column("m.v[1]"), vz = column("m.v[2]"), z = column("m.p[2]");
  const auto vx = column("m.v[0]"), wx = column("m.w[0]"), wy = column("m.w[1]"), wz = column("m.w[2]");
  // Sliding: the speed down the incline grows at g (sin - mu cos) (least
  // squares over 0.35 .. 0.7 s, while it slides on its face).
  const double theta = std::atan(0.5 / 0.86), expected = 9.81 * (std::sin(theta) - 0.3 * std::cos(theta));
  const double dy = std::cos(theta), dz = -std::sin(theta);
  double st = 0, sv = 0, stt = 0, stv = 0;
  int n = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (t[i] < 0.35 || t[i] > 0.7) continue;
    const double v = vy[i] * dy + vz[i] * dz;
    st += t[i], sv += v, stt += t[i] * t[i], stv += t[i] * v, ++n;
  }
  const double slope = (n * stv - st * sv) / (n * stt - st * st);
  EXPECT_NEAR(slope, expected, 0.01 * expected);
  // Comes to rest on the floor, resting on its face.
  EXPECT_LT(std::abs(vy.back()) + std::abs(vz.back()), 1e-3);
  EXPECT_NEAR(z.back(), 0.1, 1e-3);
  // Mechanical energy never exceeds its start (no external work; the contact
  // springs only store what they later give back, less their damping).
  const double inertia = 1.0 * 0.2 * 0.2 / 6;
  double e0 = 0, worst = -1e300;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double e = 0.5 * (vx[i] * vx[i] + vy[i] * vy[i] + vz[i] * vz[i]) +
                     0.5 * inertia * (wx[i] * wx[i] + wy[i] * wy[i] + wz[i] * wz[i]) + 9.81 * z[i];
    if (i == 0) e0 = e;
    worst = std::max(worst, e - e0);
  }
  EXPECT_LE(worst, 1e-9);
}

TEST(ContactTest, BeamOnCounterRotatingRollersOscillatesCT3) {
  const std::string path = std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/rollers.xml";
  {
    const auto loaded = diagrams::LoadDiagram(path, {});
    blocks::Simulator sim(*loaded.diagram, loaded.solver, loaded.logged);
    ASSERT_TRUE(sim.Run().ok);
    const auto t = sim.results().Column(0), y = sim.results().Column(sim.results().FindColumn("m.y"));
    std::vector<double> crossings;
    for (std::size_t i = 1; i < t.size(); ++i)
      if (y[i - 1] > 0 && y[i] <= 0) crossings.push_back(t[i - 1] + (t[i] - t[i - 1]) * y[i - 1] / (y[i - 1] - y[i]));
    ASSERT_GE(crossings.size(), 3u);
    const double period = (crossings.back() - crossings.front()) / (crossings.size() - 1);
    EXPECT_NEAR(period, 2 * M_PI * std::sqrt(0.5 / (0.3 * 9.81)), 0.005 * 2.590);  // 2.590 s
    EXPECT_NEAR(*std::max_element(y.begin(), y.end()), 0.1, 1e-3);  // no growth, no decay
  }
  {
    // rollers reversed: the beam runs away
    diagrams::LoadOptions options;
    options.overrides = {{"Omega", -10}};
    options.t_end = 3;
    const auto loaded = diagrams::LoadDiagram(path, options);
    blocks::Simulator sim(*loaded.diagram, loaded.solver, loaded.logged);
    ASSERT_TRUE(sim.Run().ok);
    const auto y = sim.results().Column(sim.results().FindColumn("m.y"));
    EXPECT_GT(y.back(), 1.0);
  }
}

}  // namespace
}  // namespace mechflow
