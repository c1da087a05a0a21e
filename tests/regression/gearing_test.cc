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

#include <algorithm>
#include <string>

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace mechflow
