// The tension mechanism (../shared/TENSION.md, ELEMENTS.md 10, test TM-1):
// the full closed-loop multibody model against an independent computation,
// the exact reduced one-degree-of-freedom equation of the lever angle
//   I(phi) phi'' + 1/2 I'(phi) phi'^2 = (F_spring - F_contact) dL/dphi,
// integrated here by classical Runge-Kutta with a 1 us step.

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "blocks/simulator.h"
#include "diagrams/loader.h"

namespace mechflow {
namespace {

constexpr double kB = 0.05, kA = 0.03, kH = 0.1;
constexpr double kIo1 = 2.843445e-2, kM2 = 0.5, kIo2 = 0.1, kIo3 = 1.13983182e-2;

double Length(double phi) { return std::sqrt(kB * kB + kH * kH + 2 * kB * kH * std::sin(phi)) - kA; }
double LengthRate(double phi) { return kB * kH * std::cos(phi) / (Length(phi) + kA); }
double GuideRate(double phi) {  // d phi2 / d phi1
  const double r = Length(phi) + kA;
  return (kB * kB + kH * kB * std::sin(phi)) / (r * r);
}
double Inertia(double phi) {
  const double dl = LengthRate(phi), dg = GuideRate(phi), l = Length(phi);
  return kIo1 + kM2 * (dl * dl + l * l * dg * dg) + (kIo2 + kIo3) * dg * dg;
}

const double kL0 = Length(-M_PI / 4);

double ContactForce(double delta, double rate) {
  if (delta <= 0) return 0.0;
  const double d = std::min(delta / 0.002, 1.0);
  return std::max(0.0, 2e5 * delta * delta + 500 * d * d * (3 - 2 * d) * rate);
}

struct Peak {
  double force = 0, time = 0;
};

Peak ReducedModelPeak() {
  auto accel = [](double phi, double w) {
    const double h = 1e-6;
    const double di = (Inertia(phi + h) - Inertia(phi - h)) / (2 * h);
    const double l = Length(phi), dl = LengthRate(phi);
    const double spring = 1000 * (0.1 - (l - kL0));
    const double contact = ContactForce(l - kL0 - 0.03, dl * w);
    return ((spring - contact) * dl - 0.5 * di * w * w) / Inertia(phi);
  };
  double phi = -M_PI / 4, w = 0, t = 0;
  const double h = 1e-6;
  Peak peak;
  while (t < 0.12) {
    const double k1p = w, k1w = accel(phi, w);
    const double k2p = w + 0.5 * h * k1w, k2w = accel(phi + 0.5 * h * k1p, w + 0.5 * h * k1w);
    const double k3p = w + 0.5 * h * k2w, k3w = accel(phi + 0.5 * h * k2p, w + 0.5 * h * k2w);
    const double k4p = w + h * k3w, k4w = accel(phi + h * k3p, w + h * k3w);
    phi += h / 6 * (k1p + 2 * k2p + 2 * k3p + k4p);
    w += h / 6 * (k1w + 2 * k2w + 2 * k3w + k4w);
    t += h;
    const double f = ContactForce(Length(phi) - kL0 - 0.03, LengthRate(phi) * w);
    if (f > peak.force) peak = {f, t};
  }
  return peak;
}

TEST(TensionMechanismTest, PeakContactForceTM1AgainstTheExactReducedModel) {
  diagrams::LoadOptions options;
  options.overrides = {{"dt_out", 1e-5}};
  options.t_end = 0.15;
  const auto loaded = diagrams::LoadDiagram(std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/tension_mechanism.xml",
                                            options);
  blocks::Simulator sim(*loaded.diagram, loaded.solver, loaded.logged);
  ASSERT_TRUE(sim.Run().ok);
  const auto& r = sim.results();
  const auto force = r.Column(r.FindColumn("contact force")), t = r.Column(0);
  const auto top = std::max_element(force.begin(), force.end());
  const Peak multibody{*top, t[top - force.begin()]};
  const Peak reduced = ReducedModelPeak();
  // the two readings of the same mechanics agree
  EXPECT_NEAR(multibody.force, reduced.force, 1e-3 * reduced.force);
  EXPECT_NEAR(multibody.time, reduced.time, 2e-5);
  // TM-1 and the paper (284.14 N at 0.09 s, from polynomial kinematics)
  EXPECT_NEAR(multibody.force, 284.0, 3.0);
  EXPECT_GE(multibody.time, 0.09);
  EXPECT_LE(multibody.time, 0.095);
  std::printf("peak contact force: multibody %.3f N at %.5f s, reduced %.3f N at %.5f s, paper 284.14 N at 0.09 s\n",
              multibody.force, multibody.time, reduced.force, reduced.time);
}

}  // namespace
}  // namespace mechflow
