// A contact that starts deeper than its max_penetration never crosses the
// bound, so the run's warning never comes: loading warns instead, naming the
// contact's line and the depth, and says when the plane's normal likely
// points into the body (its centre of mass is beyond the plane too). A
// contact preloaded within its bound is a rest state: no warning.

#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/cli/mechflow_command.h"

namespace mechflow {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

// d.xml in a fresh folder: a 0.1 m ball at height z on a translational
// joint, its contact `contact` (line 5) against the floor z = 0 of Base0.
fs::path Write(const std::string& name, double z, const std::string& contact) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("contact_start_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "d.xml") << "<diagram name='d'>\n<mechanism name='m'>\n"
                               << "<body name='Ball' mass='1' inertia='1 1 1'/>\n"
                               << "<joint name='j' type='translational' body1='Base0' body2='Ball' axis='0 0 1' q0='"
                               << z << "'/>\n"
                               << contact << "\n</mechanism>\n<solver t_end='0.001'/>\n</diagram>\n";
  return dir / "d.xml";
}

// Bottom, top and side of the ball.
const std::string kPoints =
    "<contact name='floor' type='points_plane' body1='Ball' points='0 0 -0.1; 0 0 0.1; 0.1 0 0' body2='Base0' "
    "stiffness='1e5' ";

TEST(ContactStartTest, ABallFiveCentimetresInsideWarnsNamingTheContactLineAndDepth) {
  const fs::path xml = Write("inside", 0.05, kPoints + "normal='0 0 1' max_penetration='0.01'/>");
  const auto check = testing::RunMechflow("check " + xml.string());
  ASSERT_EQ(check.exit_code, 0) << check.err;
  EXPECT_THAT(check.out, HasSubstr(xml.string() + ":5: warning: contact 'floor' starts 0.05 m (50 mm) inside its "
                                                  "plane, beyond its max_penetration 0.01 m (10 mm)"));
  EXPECT_THAT(check.out, HasSubstr(": ok (1 warning)"));
  // the centre of mass is outside: a body too deep, not a normal the wrong way
  EXPECT_THAT(check.out, Not(HasSubstr("normal likely")));
  const auto run = testing::RunMechflow("run " + xml.string() + " --out " + (xml.parent_path() / "out").string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_THAT(run.err, HasSubstr(":5: warning: contact 'floor' starts 0.05 m (50 mm)"));
}

// A ball resting on a floor whose normal points down is inside by its whole
// height; so is a wheel (circle) on it.
TEST(ContactStartTest, AFlippedNormalWarnsThatItPointsIntoTheBody) {
  const fs::path points = Write("flipped_points", 0.1, kPoints + "normal='0 0 -1' max_penetration='0.01'/>");
  const auto check = testing::RunMechflow("check " + points.string());
  ASSERT_EQ(check.exit_code, 0) << check.err;
  EXPECT_THAT(check.out, HasSubstr(points.string() + ":5: warning: contact 'floor' starts 0.2 m (200 mm) inside"));
  EXPECT_THAT(check.out, HasSubstr("the plane's normal likely points into 'Ball'"));
  const fs::path circle =
      Write("flipped_circle", 0.1,
            "<contact name='wheel' type='circle_plane' body1='Ball' circle_normal='1 0 0' radius='0.1' body2='Base0' "
            "normal='0 0 -1' stiffness='1e5'/>");
  const auto wheel = testing::RunMechflow("check " + circle.string());
  ASSERT_EQ(wheel.exit_code, 0) << wheel.err;
  EXPECT_THAT(wheel.out, HasSubstr(circle.string() + ":5: warning: contact 'wheel' starts 0.2 m (200 mm) inside"));
  EXPECT_THAT(wheel.out, HasSubstr("the plane's normal likely points into 'Ball'"));
}

TEST(ContactStartTest, APreloadedContactWithinItsBoundDoesNotWarn) {
  const fs::path xml = Write("preloaded", 0.095, kPoints + "normal='0 0 1' max_penetration='0.01'/>");
  const auto check = testing::RunMechflow("check " + xml.string());
  ASSERT_EQ(check.exit_code, 0) << check.err;
  EXPECT_THAT(check.out, Not(HasSubstr("warning")));
}

// Without the attribute the bound is 0.05 m: 4 cm in is a rest state, 6 cm not.
TEST(ContactStartTest, TheDefaultBoundAppliesTheSameRule) {
  const fs::path within = Write("default_within", 0.06, kPoints + "normal='0 0 1'/>");
  const auto quiet = testing::RunMechflow("check " + within.string());
  ASSERT_EQ(quiet.exit_code, 0) << quiet.err;
  EXPECT_THAT(quiet.out, Not(HasSubstr("warning")));
  const fs::path beyond = Write("default_beyond", 0.04, kPoints + "normal='0 0 1'/>");
  const auto check = testing::RunMechflow("check " + beyond.string());
  ASSERT_EQ(check.exit_code, 0) << check.err;
  EXPECT_THAT(check.out, HasSubstr(":5: warning: contact 'floor' starts 0.06 m (60 mm) inside its plane, beyond "
                                   "its max_penetration 0.05 m (50 mm)"));
}

}  // namespace
}  // namespace mechflow
