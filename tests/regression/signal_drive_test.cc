// Joint coordinates driven by signals (motion_sine, motion_filter,
// motion_table into a tt/rt transformation with signal="NAME"), against
// closed forms: the steady response of a base-excited spring-mass, of the
// same through the filter, of the linear quarter car on a sinusoidal road,
// and the kinematics of a slider-crank whose crank follows a signal.

#include <cmath>
#include <complex>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/numbers.h"
#include "tests/test_util.h"

namespace mechflow {
namespace {

using ::testing::HasSubstr;
using Complex = std::complex<double>;
using mechflow::testing::kPi;

// Amplitude and phase (y = A sin(w t + phase)) of y over the whole periods
// of w that end at the last row, by projection (trapezoid rule).
struct Harmonic {
  double amplitude, phase;
};
Harmonic Fit(const std::vector<double>& t, const std::vector<double>& y, double w, int periods) {
  const double t0 = t.back() - periods * 2 * kPi / w;
  double s = 0, c = 0;
  for (std::size_t i = 1; i < t.size(); ++i) {
    if (t[i - 1] < t0 - 1e-12) continue;
    const double dt = t[i] - t[i - 1];
    s += 0.5 * dt * (y[i] * std::sin(w * t[i]) + y[i - 1] * std::sin(w * t[i - 1]));
    c += 0.5 * dt * (y[i] * std::cos(w * t[i]) + y[i - 1] * std::cos(w * t[i - 1]));
  }
  const double span = t.back() - t0;
  s *= 2 / span;
  c *= 2 / span;
  return {std::hypot(s, c), std::atan2(c, s)};
}

// A mass on a spring and damper whose other end, a footprint body, follows
// the signal `drive`; `blocks` feed it.
std::string BaseExcited(const std::string& blocks, double t_end) {
  std::ostringstream xml;
  xml << "<diagram><identifiers><identifier name='m' value='2'/><identifier name='k' value='2*(2*pi)^2'/>"
         "<identifier name='c' value='2*0.2*sqrt(k*m)'/></identifiers>"
         "<mechanism name='mech' gravity='0 0 0'>"
         "<body name='Base' mass='1' inertia='1 1 1'/><body name='Mass' mass='m' inertia='1 1 1'/>"
         "<joint name='jBase' type='generalized' body1='Base0' body2='Base'><et type='tt' axis='0 0 1' "
         "signal='drive'/></joint>"
         "<joint name='jMass' type='translational' body1='Base0' body2='Mass' axis='0 0 1' q0='1'/>"
         "<force name='spring' type='linear' body1='Base' body2='Mass' c='k' d='c'/>"
         "<sensor name='z' kind='coordinate' dof='jMass'/>"
         "<sensor name='base' kind='position' body='Base' component='z'/></mechanism>"
         "<blocks>"
      << blocks << "</blocks><connections><connect from='source.y' to='mech.drive'/>"
      << (blocks.find("motion_filter") != std::string::npos ? "<connect from='input.y' to='source.u'/>" : "")
      << "</connections><solver t_end='" << t_end << "' rtol='1e-9' atol='1e-12'/>"
      << "<output interval='0.001'><log signal='mech.z'/><log signal='mech.base'/></output></diagram>";
  return xml.str();
}

// X / Y of m x'' + c (x' - y') + k (x - y) = 0.
Complex Transmissibility(double w) {
  const double m = 2, k = 2 * std::pow(2 * kPi, 2), c = 2 * 0.2 * std::sqrt(k * m);
  const Complex jw(0, w);
  return (k + c * jw) / (k + c * jw - m * w * w);
}

TEST(SignalDriveTest, BaseExcitedSpringMassFollowsTheClosedForm) {
  const double f = 1.5, w = 2 * kPi * f, amplitude = 0.01;
  const auto run = testing::RunXml(BaseExcited(
      "<block type='motion_sine' name='source' amplitude='0.01' frequency='1.5'/>", 20));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto t = run.Column("time"), z = run.Column("mech.z"), base = run.Column("mech.base");
  // the footprint follows the signal exactly
  for (std::size_t i = 0; i < t.size(); i += 97) EXPECT_NEAR(base[i], amplitude * std::sin(w * t[i]), 1e-15);
  std::vector<double> x(z.size());
  for (std::size_t i = 0; i < z.size(); ++i) x[i] = z[i] - 1;
  const Harmonic h = Fit(t, x, w, 6);
  const Complex expected = Transmissibility(w);
  EXPECT_NEAR(h.amplitude / amplitude, std::abs(expected), 1e-6 * std::abs(expected));
  EXPECT_NEAR(h.phase, std::arg(expected), 1e-6);
  // above resonance (1 Hz) the mass moves less than its base
  EXPECT_LT(h.amplitude / amplitude, 0.9);
}

TEST(SignalDriveTest, FilteredSignalAddsTheFiltersTransferFunction) {
  // a plain sine through motion_filter (10 Hz, zeta 0.7): the base moves by
  // the filter's response, and the mass by both
  const double f = 1.5, w = 2 * kPi * f, amplitude = 0.01;
  const auto run = testing::RunXml(BaseExcited(
      "<block type='sine' name='input' amplitude='0.01' frequency='1.5'/>"
      "<block type='motion_filter' name='source' frequency='10' damping='0.7'/>",
      20));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto t = run.Column("time"), z = run.Column("mech.z"), base = run.Column("mech.base");
  const double wf = 2 * kPi * 10;
  const Complex filter = wf * wf / (wf * wf - w * w + Complex(0, 2 * 0.7 * wf * w));
  const Harmonic hb = Fit(t, base, w, 6);
  EXPECT_NEAR(hb.amplitude / amplitude, std::abs(filter), 1e-6);
  EXPECT_NEAR(hb.phase, std::arg(filter), 1e-6);
  std::vector<double> x(z.size());
  for (std::size_t i = 0; i < z.size(); ++i) x[i] = z[i] - 1;
  const Harmonic h = Fit(t, x, w, 6);
  const Complex expected = filter * Transmissibility(w);
  EXPECT_NEAR(h.amplitude / amplitude, std::abs(expected), 1e-6 * std::abs(expected));
  EXPECT_NEAR(h.phase, std::arg(expected), 1e-6);
  // the filter starts at rest on its input (0 at t = 0): no jump
  EXPECT_EQ(base.front(), 0.0);
}

// Z_body / Z_road of the linear quarter car (friction damper off).
Complex QuarterCarBody(double w) {
  const double ms = 400, mu = 40, ks = 2e4, cs = 1000, kt = 2e5;
  const Complex s = ks + Complex(0, w * cs);
  // [-ms w^2 + s, -s; -s, -mu w^2 + s + kt] [Zb; Zw] = [0; kt]
  const Complex a = -ms * w * w + s, b = -s, d = -mu * w * w + s + kt;
  return -b * kt / (a * d - b * b);
}

TEST(SignalDriveTest, QuarterCarOnASinusoidalRoadFollowsTheTwoDofClosedForm) {
  // the example with the friction damper off, on a road of 0.01 sin(2 pi x / 8)
  // sampled every 0.25 m (a cubic spline through it) at 20 m/s: 2.5 Hz
  std::ostringstream road;
  for (int i = 0; i <= 1200; ++i) road << (i ? "; " : "") << 0.25 * i << ' ' << 0.01 * std::sin(2 * kPi * 0.25 * i / 8);
  std::ostringstream xml;
  xml << "<diagram><identifiers><identifier name='friction' value='0'/></identifiers>"
         "<mechanism name='car' gravity='0 0 0'>"
         "<body name='Footprint' mass='1' inertia='1 1 1'/><body name='Wheel' mass='40' inertia='1 1 1'/>"
         "<body name='Body' mass='400' inertia='1 1 1'/>"
         "<joint name='jRoad' type='generalized' body1='Base0' body2='Footprint'>"
         "<et type='tt' axis='0 0 1' signal='road'/></joint>"
         "<joint name='jWheel' type='translational' body1='Base0' body2='Wheel' axis='0 0 1' q0='0.3'/>"
         "<joint name='jBody' type='translational' body1='Base0' body2='Body' axis='0 0 1' q0='0.6'/>"
         "<force name='tyre' type='linear' body1='Footprint' body2='Wheel' c='2e5'/>"
         "<force name='spring' type='linear' body1='Wheel' body2='Body' c='2e4' d='1000'/>"
         "<sensor name='z_body' kind='coordinate' dof='jBody'/></mechanism>"
         "<blocks><block type='motion_table' name='profile' speed='20' points='"
      << road.str()
      << "'/></blocks><connections><connect from='profile.y' to='car.road'/></connections>"
         "<solver t_end='12' rtol='1e-9' atol='1e-12'/><output interval='0.001'><log signal='car.z_body'/>"
         "</output></diagram>";
  const auto run = testing::RunXml(xml.str());
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto t = run.Column("time"), z = run.Column("car.z_body");
  std::vector<double> x(z.size());
  for (std::size_t i = 0; i < z.size(); ++i) x[i] = z[i] - 0.6;
  const double w = 2 * kPi * 20 / 8;
  const Harmonic h = Fit(t, x, w, 10);
  const Complex expected = QuarterCarBody(w);
  // the spline of a sine sampled at 32 points per wavelength is that sine to
  // about (2 pi / 32)^4 / 384 = 4e-6 of its amplitude (measured: 1.0e-5 rad
  // of phase)
  EXPECT_NEAR(h.amplitude / 0.01, std::abs(expected), 3e-5 * std::abs(expected));
  EXPECT_NEAR(h.phase, std::arg(expected), 3e-5);
}

TEST(SignalDriveTest, TheQuarterCarExampleRunsOverItsRoad) {
  const auto loaded = diagrams::LoadDiagram(std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/quarter_car.xml");
  blocks::Simulator sim(*loaded.diagram, loaded.solver, loaded.logged);
  const blocks::RunOutcome outcome = sim.Run();
  ASSERT_TRUE(outcome.ok) << outcome.failure;
  // the footprint rides the road: at 20 m/s the bump's crest (x = 101 m) is
  // passed at t = 5.05 s, 0.05 + 0.01 sin(2 pi 101 / 8) high
  const auto t = sim.results().Column(sim.results().FindColumn("time"));
  const auto road = sim.results().Column(sim.results().FindColumn("road"));
  const std::size_t crest = static_cast<std::size_t>(std::lround(5.05 / 0.002));
  EXPECT_NEAR(t[crest], 5.05, 1e-12);
  EXPECT_NEAR(road[crest], 0.05 + 0.01 * std::sin(2 * kPi * 101 / 8), 1e-6);
}

TEST(SignalDriveTest, ADrivenCrankCarriesTheSliderCrankLoopFromItsStartingAngle) {
  // crank angle theta = pi/3 + 0.5 sin(2 pi t) from a signal; the loop
  // assembles at pi/3 (not at 0, the value before inputs are valid) and the
  // slider follows s = a cos(theta) + sqrt(b^2 - (a sin(theta) - e)^2)
  const double a = 0.1, b = 0.3;
  const std::string xml =
      "<diagram><mechanism name='m' gravity='0 0 0'>"
      "<body name='Crank' mass='1' inertia='1e-3 1e-3 1e-3'/><body name='Rod' mass='1' inertia='1e-3 1e-3 1e-3'/>"
      "<body name='Slider' mass='1' inertia='1e-3 1e-3 1e-3'/>"
      "<joint name='j1' type='generalized' body1='Base0' body2='Crank'><et type='rt' axis='0 0 1' "
      "signal='crank'/></joint>"
      "<joint name='j2' type='rotational' body1='Crank' point1='0.1 0 0' body2='Rod' axis='0 0 1' q0='-1.2'/>"
      "<joint name='j3' type='rotational' body1='Rod' point1='0.3 0 0' body2='Slider' axis='0 0 1' q0='0.2'/>"
      "<joint name='j4' type='translational' body1='Base0' body2='Slider' axis='1 0 0' q0='0.33'/>"
      "<sensor name='s' kind='coordinate' dof='j4'/></mechanism>"
      "<blocks><block type='motion_sine' name='source' bias='pi/3' amplitude='0.5' frequency='1'/></blocks>"
      "<connections><connect from='source.y' to='m.crank'/></connections>"
      "<solver t_end='2' rtol='1e-10' atol='1e-12'/><output interval='0.01'><log signal='m.s'/></output></diagram>";
  const auto run = testing::RunXml(xml);
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto t = run.Column("time"), s = run.Column("m.s");
  double worst = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double theta = kPi / 3 + 0.5 * std::sin(2 * kPi * t[i]);
    const double exact = a * std::cos(theta) + std::sqrt(b * b - std::pow(a * std::sin(theta), 2));
    worst = std::max(worst, std::abs(s[i] - exact));
  }
  EXPECT_LT(worst, 1e-8);
}

// Wirings that cannot take effect are refused, naming what to do instead.
TEST(SignalDriveTest, WrongWiringsAreRefused) {
  const auto load = [](const std::string& et, const std::string& blocks, const std::string& connect) {
    return testing::InputErrorOf([&] {
      testing::LoadXml("<diagram><identifiers><identifier name='u' value='0'/></identifiers>"
                       "<mechanism name='m' gravity='0 0 0'><input name='u'/>"
                       "<body name='B' mass='1' inertia='1 1 1'/><joint name='j' type='generalized' body1='Base0' "
                       "body2='B'>" +
                       et + "</joint></mechanism><blocks>" + blocks + "</blocks><connections>" + connect +
                       "</connections><solver t_end='1'/></diagram>");
    });
  };
  const std::string sine = "<block type='sine' name='s'/>";
  const std::string motion = "<block type='motion_sine' name='s'/>";
  // a plain signal has no derivatives to give
  EXPECT_THAT(load("<et type='tt' axis='1 0 0' signal='d'/>", sine, "<connect from='s.y' to='m.d'/>"),
              HasSubstr("width mismatch"));
  EXPECT_THAT(load("<et type='tt' axis='1 0 0' signal='d' value='t'/>", motion, "<connect from='s.y' to='m.d'/>"),
              HasSubstr("give either 'value' (a function of t) or 'signal', not both"));
  EXPECT_THAT(load("<et type='tt' axis='1 0 0' signal='u'/>", motion, "<connect from='s.y' to='m.u'/>"),
              HasSubstr("has the name of an <input>"));
  EXPECT_THAT(load("<et type='tt' axis='1 0 0' signal='d'/>", motion, ""), HasSubstr("is not connected"));
  EXPECT_THAT(load("<et type='tv' axis='1 0 0' signal='d'/>", motion, "<connect from='s.y' to='m.d'/>"),
              HasSubstr("signal"));
}

}  // namespace
}  // namespace mechflow
