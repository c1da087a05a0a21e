// Exact stick (docs/ELEMENTS.md 3.6): a frictional element with stick="exact" is
// held by a constraint force while it sticks (mech/exact_stick.h), so
//   - the Coulomb oscillator (FR-2: m = 10 kg, k = 1000 N/m, x0 = 0.105 m,
//     F = 10 N, ratio 1.2) reverses without a stick phase and stops for good
//     at x = -0.005 m, t = 5 pi sqrt(m/k), both to 1e-9;
//   - a block on a 30 degree slope whose static friction exceeds its weight's
//     pull holds exactly, with the friction equal to m g sin(theta);
//   - a force ramp breaks the box away exactly when it reaches ratio * F;
// on a joint coordinate and between two points alike.
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/numbers.h"
#include "tests/test_util.h"

namespace mechflow {
namespace {

using mechflow::testing::kPi;

// FR-2 with the friction on the joint coordinate or on a line from a point
// of the ground far out along -x (so the line stays along the motion).
std::string CoulombOscillator(bool on_line, const std::string& solver) {
  const std::string friction =
      on_line ? "<force name='friction' type='frictional' body1='Base0' point1='-10 0 0' body2='Box' "
                "friction='10' ratio='1.2' stick='exact'/>"
              : "<joint_force name='friction' dof='j' type='frictional' friction='10' ratio='1.2' stick='exact'/>";
  return "<diagram name='fr2'><mechanism name='m' gravity='0 0 0'>"
         "<body name='Box' mass='10' inertia='1 1 1'/>"
         "<joint name='j' type='translational' body1='Base0' body2='Box' axis='1 0 0' q0='0.105'/>"
         "<joint_force name='spring' dof='j' type='linear' c='1000' x0='0'/>" +
         friction +
         "<sensor name='x' kind='coordinate' dof='j'/><sensor name='v' kind='velocity' dof='j'/>"
         "<sensor name='mode' kind='element' element='friction' quantity='mode'/>"
         "<sensor name='force' kind='element' element='friction'/></mechanism>" +
         solver +
         "<output interval='0.01'><log signal='m.x'/><log signal='m.v'/><log signal='m.mode'/>"
         "<log signal='m.force'/></output></diagram>";
}

void ExpectExactCoulombStop(const testing::XmlRun& run) {
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const double half_period = kPi * std::sqrt(10.0 / 1000.0);
  // Five velocity zeros: four reversals (each one event, no stick phase) and
  // the stop, every half period.
  const auto& events = run.sim->events();
  ASSERT_EQ(events.size(), 5u);
  for (std::size_t n = 0; n < events.size(); ++n)
    EXPECT_NEAR(events[n].time, (n + 1) * half_period, 1e-9) << "velocity zero " << n + 1;
  const auto x = run.Column("m.x"), v = run.Column("m.v"), mode = run.Column("m.mode"),
             force = run.Column("m.force");
  EXPECT_NEAR(x.back(), -0.005, 1e-9);
  EXPECT_LT(std::abs(v.back()), 1e-12);  // what the stop event left (2e-16 measured), held
  EXPECT_EQ(mode.back(), 0.0);
  EXPECT_NEAR(force.back(), -5.0, 1e-6);  // it holds the spring's 5 N pull
}

TEST(ExactStickTest, CoulombOscillatorStopsExactlyOnAJointCoordinate) {
  ExpectExactCoulombStop(
      testing::RunXml(CoulombOscillator(false, "<solver t_end='3' rtol='1e-10' atol='1e-12'/>")));
}

TEST(ExactStickTest, CoulombOscillatorStopsExactlyBetweenTwoPoints) {
  ExpectExactCoulombStop(
      testing::RunXml(CoulombOscillator(true, "<solver t_end='3' rtol='1e-10' atol='1e-12'/>")));
}

TEST(ExactStickTest, TheStopConvergesWithTheTolerance) {
  // The stop is where the integrated v crosses zero, so it is as accurate as
  // v: measured 2.4e-6, 1.5e-8, 1.6e-10, 1.3e-12 s early at rtol 1e-6, 1e-8,
  // 1e-10, 1e-12.
  double last_error = 1.0;
  for (const double rtol : {1e-6, 1e-8, 1e-10, 1e-12}) {
    std::ostringstream solver;
    solver << "<solver t_end='3' rtol='" << rtol << "' atol='" << rtol * 1e-2 << "'/>";
    const auto run = testing::RunXml(CoulombOscillator(false, solver.str()));
    ASSERT_TRUE(run.outcome.ok) << rtol << ": " << run.outcome.failure;
    ASSERT_EQ(run.sim->events().size(), 5u) << rtol;
    const double error = std::abs(run.sim->events().back().time - 5 * kPi * std::sqrt(0.01));
    EXPECT_LT(error, 10 * rtol) << rtol;
    EXPECT_LT(error, last_error) << rtol;
    // the position carries the error of five half periods: measured 1e-6,
    // 2.7e-8, 6.5e-10, 2.4e-11 m
    EXPECT_NEAR(run.Column("m.x").back(), -0.005, 50 * rtol) << rtol;
    last_error = error;
  }
}

// A 1 kg block on a 30 degree slope (its joint slides along the slope), held
// by friction F with static limit ratio * F = 0.6 m g cos(theta) > m g
// sin(theta): it must not move at all.
std::string Incline(const std::string& friction) {
  return "<diagram name='incline'><identifiers><identifier name='th' value='pi/6'/></identifiers>"
         "<mechanism name='m' gravity='0 0 -9.81'>"
         "<body name='Block' mass='1' inertia='1 1 1'/>"
         "<joint name='j' type='translational' body1='Base0' body2='Block' axis='cos(th) 0 -sin(th)'/>" +
         friction +
         "<sensor name='x' kind='coordinate' dof='j'/><sensor name='v' kind='velocity' dof='j'/>"
         "<sensor name='force' kind='element' element='friction'/></mechanism>"
         "<solver t_end='10' rtol='1e-10' atol='1e-14'/>"
         "<output interval='0.05'><log signal='m.x'/><log signal='m.v'/><log signal='m.force'/></output>"
         "</diagram>";
}

TEST(ExactStickTest, ABlockOnASlopeHoldsExactly) {
  for (const char* where : {"joint", "line"}) {
    const std::string friction =
        std::string(where) == "joint"
            ? "<joint_force name='friction' dof='j' type='frictional' friction='0.5*9.81*cos(th)' ratio='1.2' "
              "stick='exact'/>"
            : "<force name='friction' type='frictional' body1='Base0' point1='-5*cos(th) 0 5*sin(th)' body2='Block' "
              "friction='0.5*9.81*cos(th)' ratio='1.2' stick='exact'/>";
    const auto run = testing::RunXml(Incline(friction));
    ASSERT_TRUE(run.outcome.ok) << where << ": " << run.outcome.failure;
    EXPECT_TRUE(run.sim->events().empty()) << where;
    double drift = 0.0, speed = 0.0;
    for (double x : run.Column("m.x")) drift = std::max(drift, std::abs(x));
    for (double v : run.Column("m.v")) speed = std::max(speed, std::abs(v));
    EXPECT_LT(drift, 1e-13) << where;
    EXPECT_LT(speed, 1e-13) << where;
    // the friction carries the weight's pull down the slope, 9.81 sin 30 = 4.905 N
    EXPECT_NEAR(run.Column("m.force").back(), -4.905, 1e-9) << where;
  }
}

TEST(ExactStickTest, TheSameSlopeSlidesWhenTheStaticLimitIsBelowThePull) {
  // limit 1.0 * 0.5 g cos 30 = 4.248 N < 4.905 N: slides from the start with
  // a = g (sin 30 - 0.5 cos 30)
  const auto run = testing::RunXml(Incline(
      "<joint_force name='friction' dof='j' type='frictional' friction='0.5*9.81*cos(th)' ratio='1' "
      "stick='exact'/>"));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const double a = 9.81 * (0.5 - 0.5 * std::cos(kPi / 6));
  EXPECT_NEAR(run.Column("m.v").back(), a * 10.0, 1e-7);
  EXPECT_NEAR(run.Column("m.x").back(), 0.5 * a * 100.0, 1e-6);
}

TEST(ExactStickTest, BreaksAwayExactlyAtTheStaticForce) {
  // a push rising at 2 N/s against F = 10 N, ratio 1.2: it breaks away at
  // 12 N, t = 6 s, and the friction drops to 10 N there
  const auto run = testing::RunXml(
      "<diagram name='ramp'><mechanism name='m' gravity='0 0 0'>"
      "<body name='Box' mass='10' inertia='1 1 1'/>"
      "<joint name='j' type='translational' body1='Base0' body2='Box' axis='1 0 0'/>"
      "<joint_force name='push' dof='j' type='expression' expression='2*t'/>"
      "<joint_force name='friction' dof='j' type='frictional' friction='10' ratio='1.2' stick='exact'/>"
      "<sensor name='x' kind='coordinate' dof='j'/><sensor name='force' kind='element' element='friction'/>"
      "</mechanism><solver t_end='7' rtol='1e-10' atol='1e-12'/>"
      "<output interval='0.01'><log signal='m.x'/><log signal='m.force'/></output></diagram>");
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  ASSERT_EQ(run.sim->events().size(), 1u);
  EXPECT_NEAR(run.sim->events()[0].time, 6.0, 1e-9);
  const auto t = run.Column("time"), x = run.Column("m.x"), force = run.Column("m.force");
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (t[i] < 6.0) {
      EXPECT_LT(std::abs(x[i]), 1e-13) << "t = " << t[i];  // round-off of the balance: 2e-14 measured
      EXPECT_NEAR(force[i], -2 * t[i], 1e-9) << "t = " << t[i];
    }
  }
  // after: m x'' = 2 t - 10 from rest at t = 6: x(7) = (t^3/3 - 10 t^2/2 ... ) / m
  auto x_of = [](double s) { return (s * s * s / 3.0 - 10.0 * s * s / 2.0) / 10.0; };
  const double expected = x_of(7.0) - x_of(6.0) - (6.0 * 6.0 - 10.0 * 6.0) / 10.0 * 1.0;
  EXPECT_NEAR(x.back(), expected, 1e-8);
  EXPECT_NEAR(force.back(), -10.0, 1e-12);
}

TEST(ExactStickTest, HoldsOnEachOtherSolvedTogether) {
  // Box 2 slides on box 1, box 1 on the ground, each through an exact
  // friction on its joint; a push 2 t on box 2. Both hold it together until
  // the upper one, limit 8 N, breaks at t = 4 s; then box 1 carries the
  // upper friction's 8 N, below its 12 N limit, and never moves.
  const auto run = testing::RunXml(
      "<diagram name='stack'><mechanism name='m' gravity='0 0 0'>"
      "<body name='Box1' mass='5' inertia='1 1 1'/><body name='Box2' mass='2' inertia='1 1 1'/>"
      "<joint name='j1' type='translational' body1='Base0' body2='Box1' axis='1 0 0'/>"
      "<joint name='j2' type='translational' body1='Box1' body2='Box2' axis='1 0 0'/>"
      "<applied_force name='push' body='Box2' force='2*t 0 0'/>"
      "<joint_force name='lower' dof='j1' type='frictional' friction='10' ratio='1.2' stick='exact'/>"
      "<joint_force name='upper' dof='j2' type='frictional' friction='8' ratio='1' stick='exact'/>"
      "<sensor name='x1' kind='coordinate' dof='j1'/><sensor name='x2' kind='coordinate' dof='j2'/>"
      "<sensor name='lower' kind='element' element='lower'/><sensor name='upper' kind='element' element='upper'/>"
      "</mechanism><solver t_end='6' rtol='1e-10' atol='1e-12'/>"
      "<output interval='0.01'><log signal='m.x1'/><log signal='m.x2'/><log signal='m.lower'/>"
      "<log signal='m.upper'/></output></diagram>");
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  ASSERT_EQ(run.sim->events().size(), 1u);
  EXPECT_NEAR(run.sim->events()[0].time, 4.0, 1e-9);
  const auto t = run.Column("time"), x1 = run.Column("m.x1"), x2 = run.Column("m.x2"),
             lower = run.Column("m.lower"), upper = run.Column("m.upper");
  for (std::size_t i = 0; i < t.size(); ++i) {
    EXPECT_LT(std::abs(x1[i]), 1e-12) << "t = " << t[i];
    EXPECT_NEAR(lower[i], -std::min(2 * t[i], 8.0), 1e-9) << "t = " << t[i];
    if (t[i] < 4.0) {
      EXPECT_NEAR(upper[i], -2 * t[i], 1e-9) << "t = " << t[i];
    }
  }
  // after the break: 2 x2'' = 2 t - 8 from rest at t = 4
  auto x_of = [](double s) { return (s * s * s / 3.0 - 4.0 * s * s) / 2.0; };
  EXPECT_NEAR(x2.back(), x_of(6.0) - x_of(4.0) - (16.0 - 32.0) / 2.0 * 2.0, 1e-8);
  EXPECT_NEAR(upper.back(), -8.0, 1e-12);
}

// A four-bar at rest under gravity held by a bearing friction on its crank:
// the holding moment comes through the loop's constraint solve. Reference:
// the same linkage held by a stiff stick spring, settled.
std::string HeldFourBar(const std::string& bearing) {
  return "<diagram name='held'><mechanism name='m'>"
         "<body name='Crank' mass='0.3' com='0 0.15 0' inertia='0.00225 1e-5 0.00225'/>"
         "<body name='Coupler' mass='0.8' com='0 0.4 0' inertia='0.0427 1e-5 0.0427'/>"
         "<body name='Rocker' mass='0.6' com='0 0.3 0' inertia='0.018 1e-5 0.018'/>"
         "<joint name='j1' type='rotational' body1='Base0' body2='Crank' axis='1 0 0' q0='1.2'/>"
         "<joint name='j2' type='rotational' body1='Crank' body2='Coupler' point1='0 0.3 0' axis='1 0 0' q0='-1'/>"
         "<joint name='j3' type='rotational' body1='Base0' body2='Rocker' point1='0 0.7 0' axis='1 0 0' q0='1.9'/>"
         "<joint name='j4' type='rotational' body1='Coupler' body2='Rocker' point1='0 0.8 0' point2='0 0.6 0' "
         "axis='1 0 0'/>" +
         bearing +
         "<sensor name='crank' kind='coordinate' dof='j1'/><sensor name='rate' kind='velocity' dof='j1'/>"
         "<sensor name='moment' kind='element' element='bearing'/></mechanism>"
         "<solver t_end='5' rtol='1e-10' atol='1e-12'/>"
         "<output interval='0.05'><log signal='m.crank'/><log signal='m.rate'/><log signal='m.moment'/></output>"
         "</diagram>";
}

TEST(ExactStickTest, HoldsAClosedLoopThroughItsConstraintSolve) {
  const auto exact = testing::RunXml(
      HeldFourBar("<joint_force name='bearing' dof='j1' type='frictional' friction='20' stick='exact'/>"));
  ASSERT_TRUE(exact.outcome.ok) << exact.outcome.failure;
  EXPECT_TRUE(exact.sim->events().empty());
  const auto crank = exact.Column("m.crank"), rate = exact.Column("m.rate"), moment = exact.Column("m.moment");
  for (std::size_t i = 0; i < crank.size(); ++i) {
    EXPECT_NEAR(crank[i], crank[0], 1e-12);
    EXPECT_LT(std::abs(rate[i]), 1e-12);
  }
  const auto spring = testing::RunXml(HeldFourBar(
      "<joint_force name='bearing' dof='j1' type='frictional' friction='20' c='1e6' d='2e3'/>"));
  ASSERT_TRUE(spring.outcome.ok) << spring.outcome.failure;
  const double reference = spring.Column("m.moment").back();
  EXPECT_GT(std::abs(reference), 0.1);  // gravity loads the crank
  EXPECT_NEAR(moment.back(), reference, 1e-5 * std::abs(reference));
  // below that moment the same bearing lets go at once
  const double limit = 0.9 * std::abs(reference);
  const auto weak = testing::RunXml(HeldFourBar(
      "<joint_force name='bearing' dof='j1' type='frictional' friction='" + std::to_string(limit) +
      "' ratio='1' stick='exact'/>"));
  ASSERT_TRUE(weak.outcome.ok) << weak.outcome.failure;
  EXPECT_GT(std::abs(weak.Column("m.crank")[1] - crank[0]), 1e-4);
}

}  // namespace
}  // namespace mechflow
