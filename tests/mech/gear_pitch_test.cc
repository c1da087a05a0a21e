// Pitch geometry of gear pairs (ELEMENTS.md 6) against values worked out by
// hand, and against what any pitch point must satisfy: it lies in the plane
// of the axes at distances r1 and r2 = r1/i from them, on a line through the
// apex (the contact generatrix). Pure arithmetic, so 1e-12 tolerances.
#include <cmath>

#include <gtest/gtest.h>

#include "mech/gear_pitch.h"

namespace mechflow::mech {
namespace {

constexpr double kTol = 1e-12;

double DistanceToLine(const Vec3& x, const Vec3& o, const Vec3& a) { return (x - o).cross(a).norm(); }

void ExpectVec(const Vec3& got, const Vec3& expected) {
  EXPECT_NEAR((got - expected).norm(), 0.0, kTol) << got.transpose() << " vs " << expected.transpose();
}

TEST(GearPitchTest, ClassifiesTheAxes) {
  double gap = -1;
  EXPECT_EQ(ClassifyGearAxes(Vec3(0.1, 0, 0), Vec3::UnitX(), Vec3(0, 0.2, 0), Vec3::UnitY(), &gap),
            GearAxes::kIntersecting);
  EXPECT_NEAR(gap, 0.0, kTol);
  EXPECT_EQ(ClassifyGearAxes(Vec3::Zero(), Vec3::UnitX(), Vec3(0, 0.3, 0), -Vec3::UnitX(), &gap), GearAxes::kParallel);
  EXPECT_NEAR(gap, 0.3, kTol);  // the centre distance
  // the x axis and the vertical line through (0, 0.05, 0.3) pass 0.05 m apart
  EXPECT_EQ(ClassifyGearAxes(Vec3::Zero(), Vec3::UnitX(), Vec3(0, 0.05, 0.3), Vec3::UnitZ(), &gap), GearAxes::kSkew);
  EXPECT_NEAR(gap, 0.05, kTol);
}

TEST(GearPitchTest, ParallelAxes) {
  // centres 0.3 m apart across the axis (the axial offset 0.1 is ignored), i = 2: r1 = 0.2
  const PitchGeometry g = ParallelPitch(Vec3::Zero(), Vec3::UnitZ(), Vec3(0.3, 0, 0.1), 2.0);
  ASSERT_EQ(g.problem, nullptr);
  EXPECT_NEAR(g.r1, 0.2, kTol);
  ExpectVec(g.p, Vec3(0.2, 0, 0));
  ExpectVec(g.t, Vec3::UnitY());  // z x x
  EXPECT_NE(ParallelPitch(Vec3::Zero(), Vec3::UnitZ(), Vec3(0, 0, 1), 2.0).problem, nullptr);
}

TEST(GearPitchTest, BevelPairOfTheGearsSeed) {
  // Gears (ELEMENTS.md 9.14): shaft angle 90 deg, i = 2, tan g1 = 2 (63.43 deg);
  // gear 1 0.1 m from the apex has r1 = 0.2, the satellite 0.2 m away r2 = 0.1
  for (const Vec3& a2 : {Vec3(Vec3::UnitY()), Vec3(-Vec3::UnitY())}) {
    const PitchGeometry g = BevelPitch(Vec3(0.1, 0, 0), Vec3::UnitX(), Vec3(0, 0.2, 0), a2, 2.0);
    ASSERT_EQ(g.problem, nullptr);
    EXPECT_NEAR(g.shaft_angle, M_PI / 2, kTol);
    EXPECT_NEAR(g.cone_angle1, std::atan(2.0), kTol);
    EXPECT_NEAR(g.cone_angle1 * 180 / M_PI, 63.4349488, 1e-7);
    EXPECT_NEAR(g.r1, 0.2, kTol);
    ExpectVec(g.p, Vec3(0.1, 0.2, 0));
    ExpectVec(g.t, Vec3::UnitZ());  // x x y, whatever the sign of a2
  }
}

TEST(GearPitchTest, MitrePairAt60DegreesAwayFromTheOrigin) {
  // i = 1, S = 60 deg: tan g1 = sin 60 / (1 + cos 60) = tan 30 deg, the cones split S
  const Vec3 apex(1, 2, 3), e2(0.5, std::sqrt(3.0) / 2, 0);
  const PitchGeometry g = BevelPitch(apex + Vec3::UnitX(), -Vec3::UnitX(), apex + e2, e2, 1.0);
  ASSERT_EQ(g.problem, nullptr);
  EXPECT_NEAR(g.shaft_angle, M_PI / 3, kTol);
  EXPECT_NEAR(g.cone_angle1, M_PI / 6, kTol);
  EXPECT_NEAR(g.r1, 1 / std::sqrt(3.0), kTol);
  ExpectVec(g.p, Vec3(2, 2 + 1 / std::sqrt(3.0), 3));
  ExpectVec(g.t, -Vec3::UnitZ());  // (-x) x y: the sign follows a1
}

TEST(GearPitchTest, PitchPointIsOnBothPitchConesForAnyShaftAngle) {
  for (double degrees : {20.0, 60.0, 90.0, 120.0, 150.0}) {
    for (double ratio : {0.25, 0.5, 1.0, 2.0}) {
      const double s = degrees * M_PI / 180;
      if (1 + ratio * std::cos(s) <= 1e-6) continue;  // gear 1 would be a crown gear or inverted
      const Vec3 apex(0.2, -0.1, 0.4), e1 = Vec3(1, 1, 0).normalized();
      const Vec3 across = Vec3(-1, 1, 1).normalized().cross(e1).normalized();
      const Vec3 e2 = std::cos(s) * e1 + std::sin(s) * across;
      const Vec3 o1 = apex + 0.3 * e1, o2 = apex + 0.7 * e2;
      const PitchGeometry g = BevelPitch(o1, e1, o2, -e2, ratio);
      ASSERT_EQ(g.problem, nullptr) << degrees << " " << ratio;
      EXPECT_NEAR(g.shaft_angle, s, kTol);
      // r1 / r2 = i, measured from the two axis lines
      const double r1 = DistanceToLine(g.p, o1, e1), r2 = DistanceToLine(g.p, o2, e2);
      EXPECT_NEAR(r1, g.r1, kTol);
      EXPECT_NEAR(r1 / r2, ratio, 1e-10) << degrees << " " << ratio;
      // in the plane of the axes, on the side of gear 2, and t normal to it
      const Vec3 normal = e1.cross(e2).normalized();
      EXPECT_NEAR((g.p - apex).dot(normal), 0.0, kTol);
      EXPECT_GT((g.p - o1).dot(across), 0.0);
      EXPECT_NEAR(std::abs(g.t.dot(normal)), 1.0, kTol);
      // the generatrix through the apex makes g1 with axis 1
      EXPECT_NEAR(std::acos((g.p - apex).normalized().dot(e1)), g.cone_angle1, 1e-10);
    }
  }
  // crown-gear case by hand: S = 120 deg, i = 0.5: tan g1 = 0.433 / 0.75, g1 = 30 deg, g2 = 90 deg
  const Vec3 e2(-0.5, std::sqrt(3.0) / 2, 0);
  const PitchGeometry g = BevelPitch(Vec3(0.3, 0, 0), Vec3::UnitX(), 0.4 * e2, e2, 0.5);
  ASSERT_EQ(g.problem, nullptr);
  EXPECT_NEAR(g.cone_angle1, M_PI / 6, kTol);
  ExpectVec(g.p, Vec3(0.3, 0.3 / std::sqrt(3.0), 0));
  EXPECT_NEAR(g.p.dot(e2), 0.0, kTol);  // the crown gear's pitch cone is the plane normal to its axis
}

TEST(GearPitchTest, BevelProblems) {
  // S = 120 deg, i = 3: 1 + i cos S < 0, gear 1's cone would open past 90 deg
  const Vec3 e2(-0.5, std::sqrt(3.0) / 2, 0);
  EXPECT_NE(BevelPitch(Vec3(0.3, 0, 0), Vec3::UnitX(), 0.4 * e2, e2, 3.0).problem, nullptr);
  // gear 1's centre at the apex
  EXPECT_NE(BevelPitch(Vec3::Zero(), Vec3::UnitX(), Vec3(0, 0.2, 0), Vec3::UnitY(), 2.0).problem, nullptr);
}

}  // namespace
}  // namespace mechflow::mech
