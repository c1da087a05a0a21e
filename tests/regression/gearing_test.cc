// Gearing GR-1 (ELEMENTS.md 6): a spur pair on fixed axes, r1 = 0.2 m,
// r2 = 0.1 m, gear 1 driven at 10 rad/s, J2 = 0.01 kg m^2, c = 1e5 N/m,
// d = 1000 N s/m. Gear 2 ends at -20 rad/s; the teeth never pull; with a
// backlash b gear 2 gets no torque until the lost motion b/2 is taken up.
//
// ELEMENTS.md expects no overshoot from the linear law (damping ratio 1.58).
// With teeth that cannot pull, the damping term would make the force negative
// while the flank is still pressed; the flank lets go instead, gear 2 runs a
// little ahead (to -21.4 rad/s) until the other flank meets it. The test
// checks what the element must do, not the linear law's overshoot.
//
// Bevel gears (intersecting axes): a fixed pair at a 60 deg shaft angle runs
// at the ratio; the Gears seed (GR-2) keeps the satellite's spin relative to
// the carrier at -2 times the gear's, within delta/r2; skew axes are refused.

#include <algorithm>
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "blocks/solver/simulator.h"
#include "diagrams/loader.h"
#include "tests/test_util.h"

namespace mechflow {
namespace {

std::string Pair(double clearance) {
  return "<diagram>\n<mechanism name=\"m\" gravity=\"0 0 0\">\n"
         "<body name=\"Gear1\" mass=\"1\" inertia=\"0.02 0.01 0.01\"/>\n"
         "<body name=\"Gear2\" mass=\"1\" inertia=\"0.01 0.005 0.005\"/>\n"
         "<joint name=\"j1\" type=\"generalized\" body1=\"Base0\" body2=\"Gear1\">"
         "<et type=\"rt\" axis=\"1 0 0\" value=\"10*t\"/></joint>\n"
         "<joint name=\"j2\" type=\"rotational\" body1=\"Base0\" body2=\"Gear2\" point1=\"0 0.3 0\" axis=\"1 0 0\"/>\n"
         "<gearing name=\"mesh\" body1=\"Gear1\" axis1=\"1 0 0\" body2=\"Gear2\" ratio=\"2\" stiffness=\"1e5\" "
         "damping=\"1000\" clearance=\"" + std::to_string(clearance) + "\"/>\n"
         "<sensor name=\"w2\" kind=\"velocity\" dof=\"j2\"/>\n"
         "<sensor name=\"f\" kind=\"element\" element=\"mesh\"/>\n"
         "<sensor name=\"mode\" kind=\"element\" element=\"mesh\" quantity=\"mode\"/>\n"
         "</mechanism>\n<solver t_end=\"0.5\" rtol=\"1e-8\" atol=\"1e-10\"/>\n"
         "<output interval=\"0.00005\"><log signal=\"m.w2\"/><log signal=\"m.f\"/><log signal=\"m.mode\"/></output>\n"
         "</diagram>\n";
}

TEST(GearingTest, SpurPairGR1) {
  for (double clearance : {0.0, 1e-3}) {
    const auto run = testing::RunXml(Pair(clearance));
    ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
    const auto t = run.Column("time"), w2 = run.Column("m.w2"), f = run.Column("m.f"), mode = run.Column("m.mode");
    // ratio 2, external gears counter-rotate; with backlash gear 2 rattles
    // between the flanks, so its mean speed over the last 0.1 s is compared
    double mean = 0;
    int n = 0;
    for (std::size_t i = 0; i < t.size(); ++i)
      if (t[i] >= 0.4) mean += w2[i], ++n;
    mean /= n;
    EXPECT_NEAR(mean, -20.0, clearance > 0 ? 0.02 : 1e-6);
    if (clearance == 0) {
      EXPECT_NEAR(w2.back(), -20.0, 1e-6);
    }
    for (std::size_t i = 0; i < t.size(); ++i) {
      ASSERT_GE(f[i] * mode[i], 0.0) << "teeth pull at t = " << t[i];
      if (mode[i] == 0.0) {
        ASSERT_EQ(f[i], 0.0);
      }
    }
    if (clearance > 0) {
      // the lost motion b/2 = 0.5 mm is taken up at 2 m/s: no force before 0.25 ms
      for (std::size_t i = 0; i < t.size() && t[i] < 0.24e-3; ++i) ASSERT_EQ(f[i], 0.0) << t[i];
      EXPECT_GT(*std::max_element(f.begin(), f.end()), 0.0);
    }
  }
}

// Gear 1 0.1 m from the apex about x, driven at 10 rad/s; gear 2 free about
// e2 = (cos 60, sin 60, 0), 0.125 m from the apex; i = 2:
// tan g1 = 2 sin 60 / (1 + 2 cos 60), r1 = 0.1 tan g1 = 0.0866 m, r2 = r1 / 2.
// By hand, t = x cross y = z and delta' = r1 w1 + r2 w2: gear 2 ends at -20 rad/s.
TEST(GearingTest, BevelPairAtSixtyDegreesRunsAtTheRatio) {
  const std::string xml =
      "<diagram>\n<mechanism name=\"m\" gravity=\"0 0 0\">\n"
      "<body name=\"Gear1\" mass=\"1\" inertia=\"0.02 0.01 0.01\"/>\n"
      "<body name=\"Gear2\" mass=\"1\" inertia=\"0.0025 0.002 0.002\"/>\n"
      "<joint name=\"j1\" type=\"generalized\" body1=\"Base0\" body2=\"Gear1\">"
      "<et type=\"tc\" vector=\"0.1 0 0\"/><et type=\"rt\" axis=\"1 0 0\" value=\"10*t\"/></joint>\n"
      "<joint name=\"j2\" type=\"rotational\" body1=\"Base0\" body2=\"Gear2\" point1=\"0.0625 0.125*sqrt(3)/2 0\" "
      "axis=\"0.5 sqrt(3)/2 0\"/>\n"
      "<gearing name=\"mesh\" body1=\"Gear1\" axis1=\"1 0 0\" body2=\"Gear2\" axis2=\"0.5 sqrt(3)/2 0\" ratio=\"2\" "
      "stiffness=\"1e5\" damping=\"1000\"/>\n"
      "<sensor name=\"w2\" kind=\"velocity\" dof=\"j2\"/>\n"
      "<sensor name=\"f\" kind=\"element\" element=\"mesh\"/>\n"
      "</mechanism>\n<solver t_end=\"0.5\" rtol=\"1e-8\" atol=\"1e-10\"/>\n"
      "<output interval=\"0.001\"><log signal=\"m.w2\"/><log signal=\"m.f\"/></output>\n</diagram>\n";
  const auto run = testing::RunXml(xml);
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  EXPECT_NEAR(run.Column("m.w2").back(), -20.0, 1e-6);
  // steady: no torque needed, so no force (gear 2 spins freely)
  EXPECT_NEAR(run.Column("m.f").back(), 0.0, 1e-6);
}

TEST(GearingTest, SkewAxesAreRefusedWithTheElementsLine) {
  const std::string xml =
      "<diagram>\n<mechanism name=\"m\" gravity=\"0 0 0\">\n"
      "<body name=\"Gear1\" mass=\"1\" inertia=\"0.02 0.01 0.01\"/>\n"
      "<body name=\"Gear2\" mass=\"1\" inertia=\"0.01 0.005 0.005\"/>\n"
      "<joint name=\"j1\" type=\"rotational\" body1=\"Base0\" body2=\"Gear1\" axis=\"1 0 0\"/>\n"
      "<joint name=\"j2\" type=\"rotational\" body1=\"Base0\" body2=\"Gear2\" point1=\"0 0.05 0.3\" axis=\"0 0 1\"/>\n"
      "<gearing name=\"worm\" body1=\"Gear1\" axis1=\"1 0 0\" body2=\"Gear2\" axis2=\"0 0 1\" ratio=\"2\"/>\n"
      "</mechanism>\n</diagram>\n";
  EXPECT_EQ(testing::InputErrorOf([&] { testing::LoadXml(xml); }),
            "test.xml:7: gearing 'worm': the gear axes are skew (they pass 0.05 m apart); gearing needs parallel "
            "(spur) or intersecting (bevel) axes");
}

// GR-2: the Gears seed. Relative to the carrier, delta = r1 (phi_gear -
// phi_carrier) + r2 phi_satellite exactly (the pitch point is fixed in the
// carrier), so the satellite's spin is -i times the gear's, up to delta/r2.
TEST(GearingTest, GearsSeedSatelliteSpinsTwiceTheGearGR2) {
  const auto loaded =
      diagrams::LoadDiagram(std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/gears.xml", {});
  blocks::Simulator sim(*loaded.diagram, loaded.solver, loaded.logged);
  const auto outcome = sim.Run();
  ASSERT_TRUE(outcome.ok) << outcome.failure;
  const auto& r = sim.results();
  auto column = [&](const std::string& name) { return r.Column(r.FindColumn(name)); };
  const auto t = column("time"), gear = column("m.gear"), carrier = column("m.carrier");
  const auto satellite = column("m.satellite"), delta = column("m.deflection");
  const double r2 = 0.1;
  double worst_slip = 0, travel = 0, worst_identity = 0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    const double error = satellite[k] + 2 * (gear[k] - carrier[k]);
    // the spin ratio holds to within the teeth's deflection (plus the solver's tolerance)
    ASSERT_LE(std::abs(error), std::abs(delta[k]) / r2 + 1e-6) << "t = " << t[k];
    worst_identity = std::max(worst_identity, std::abs(error - delta[k] / r2));
    worst_slip = std::max(worst_slip, std::abs(delta[k]) / r2);
    travel = std::max(travel, std::abs(satellite[k]));
  }
  // the relation is not vacuous: the satellite turns through radians while
  // the teeth give by milliradians
  EXPECT_GT(travel, 1.0);
  EXPECT_LT(worst_slip, 1e-2);
  EXPECT_LT(worst_identity, 1e-6);
  // the carrier swings and the gear is driven: both move
  EXPECT_GT(*std::max_element(carrier.begin(), carrier.end()) - *std::min_element(carrier.begin(), carrier.end()), 0.5);
}

}  // namespace
}  // namespace mechflow
