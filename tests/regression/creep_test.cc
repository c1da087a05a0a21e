// CT-2 hold (ELEMENTS.md 5.4): a block resting on the Falling incline
// (external normal (0, 0.5, 0.86), theta = 30.17 deg) with mu >= tan(theta)
// does not hold under the regularised Coulomb law
//   F_t = -mu N w_t / sqrt(|w_t|^2 + v_eps^2):
// it creeps at the speed where mu N v / sqrt(v^2 + v_eps^2) = m g sin(theta),
// with N = m g cos(theta), i.e. with r = tan(theta)/mu
//   v = v_eps r / sqrt(1 - r^2)   (about v_eps tan(theta)/mu for mu >> tan(theta)).
// The block's four bottom vertices are points-plane contacts; the creep speed
// is measured along the slope after the landing transient and compared with
// the exact regularised value (1e-4 relative; it agrees to 7 digits) and with
// the estimate (to within the
// factor 1/sqrt(1 - r^2) that separates the two).

#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "tests/test_util.h"

namespace mechflow {
namespace {

// A 1 kg block, 0.2 m cube, its bottom face on the incline through the
// origin, released at rest; contacts as in falling.xml (50 Hz, damping ratio
// 0.3, shared by four vertices), gravity -9.81 z.
std::string Incline(double mu, double v_eps) {
  return "<diagram>\n<identifiers>\n"
         "<identifier name=\"m\" value=\"1\"/><identifier name=\"a\" value=\"0.1\"/>\n"
         "<identifier name=\"theta\" value=\"atan(0.5/0.86)\"/>\n"
         "<identifier name=\"c\" value=\"4*pi^2*50^2*m/4\"/>\n"
         "<identifier name=\"d\" value=\"2*0.3*sqrt(m*4*pi^2*50^2*m)/4\"/>\n"
         "<identifier name=\"mu\" value=\"" + std::to_string(mu) + "\"/>\n"
         "<identifier name=\"v_eps\" value=\"" + std::to_string(v_eps) + "\"/>\n"
         "</identifiers>\n<mechanism name=\"m\">\n"
         "<body name=\"Block\" mass=\"m\" inertia=\"m*(2*a)^2/6 m*(2*a)^2/6 m*(2*a)^2/6\"/>\n"
         // centre a above the incline point (0, -1, 0.5/0.86), face on the incline
         "<joint name=\"j\" type=\"quaternion\" body1=\"Base0\" body2=\"Block\" "
         "position=\"0 -1+a*sin(theta) 0.5/0.86+a*cos(theta)\" angles=\"-theta 0 0\"/>\n"
         "<contact name=\"incline\" type=\"points_plane\" body1=\"Block\" body2=\"Base0\" normal=\"0 0.5 0.86\" "
         "points=\"-a -a -a; a -a -a; -a a -a; a a -a\" stiffness=\"c\" damping=\"d\" mu=\"mu\" v_eps=\"v_eps\"/>\n"
         "<sensor name=\"v\" kind=\"point_velocity\" body=\"Block\"/>\n"
         "<sensor name=\"w\" kind=\"angular_velocity\" body=\"Block\"/>\n"
         "</mechanism>\n<solver t_end=\"2\" rtol=\"1e-8\" atol=\"1e-11\"/>\n"
         "<output interval=\"0.01\"><log signal=\"m.v\"/><log signal=\"m.w\"/></output>\n</diagram>\n";
}

TEST(CreepTest, RegularisedFrictionCreepsOnTheFallingInclineCT2) {
  const double theta = std::atan(0.5 / 0.86), tan_theta = std::tan(theta);
  // down the slope: the incline rises toward -y
  const double down_y = std::cos(theta), down_z = -std::sin(theta);
  for (double v_eps : {1e-3, 1e-4}) {
    for (double mu : {0.7, 1.0, 2.0, 5.0}) {
      const auto run = testing::RunXml(Incline(mu, v_eps));
      ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
      const double r = tan_theta / mu, exact = v_eps * r / std::sqrt(1 - r * r), estimate = v_eps * r;
      const auto t = run.Column("time"), vy = run.Column("m.v[1]"), vz = run.Column("m.v[2]"),
                 vx = run.Column("m.v[0]"), wx = run.Column("m.w[0]");
      // mean speed down the slope over the last second (the landing has died out by then)
      double mean = 0, lowest = 1e300, highest = -1e300;
      int n = 0;
      for (std::size_t k = 0; k < t.size(); ++k) {
        if (t[k] < 1.0) continue;
        const double v = vy[k] * down_y + vz[k] * down_z;
        mean += v, lowest = std::min(lowest, v), highest = std::max(highest, v), ++n;
        // straight down the slope, without turning (1e-3 of the creep speed; w in rad/s times 1 m)
        ASSERT_LT(std::abs(vx[k]) + std::abs(wx[k]), 1e-3 * exact) << "t = " << t[k];
      }
      mean /= n;
      // steady: the speed is constant over the window
      EXPECT_LT(highest - lowest, 1e-3 * exact) << "mu " << mu << " v_eps " << v_eps;
      EXPECT_NEAR(mean, exact, 1e-4 * exact) << "mu " << mu << " v_eps " << v_eps;
      // the estimate v_eps tan(theta)/mu is low by the factor sqrt(1 - r^2)
      EXPECT_NEAR(mean / estimate, 1 / std::sqrt(1 - r * r), 1e-4) << "mu " << mu << " v_eps " << v_eps;
      RecordProperty("creep_mu_" + std::to_string(mu) + "_veps_" + std::to_string(v_eps), std::to_string(mean));
      std::printf("mu %.2f v_eps %.0e: creep %.6e m/s, exact %.6e, estimate %.6e\n", mu, v_eps, mean, exact,
                  estimate);
    }
  }
}

}  // namespace
}  // namespace mechflow
