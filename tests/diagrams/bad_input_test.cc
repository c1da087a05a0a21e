// Bad input a model can hold by mistake, refused before the run: negative stiffness or friction, static below
// dynamic friction, a contact plane with a zero normal, a bound that is not
// positive, and <report>s that name no signal; each an InputError naming the
// file:line of the offending attribute or element (one test per rule and
// element kind).

#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/test_util.h"

namespace mechflow::diagrams::bad_input_test {  // names of its own: the files of its folder are compiled together
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;
using testing::InputErrorOf;
using testing::LoadXml;

// A mechanism with two bodies; `element` is on line 5 of test.xml.
std::string WithElement(const std::string& element) {
  return "<diagram>\n<mechanism name='m' gravity='0 0 0'>\n"
         "<body name='A' mass='1' inertia='1 1 1'/>\n"
         "<joint name='x' type='translational' body1='Base0' body2='A' axis='1 0 0'/>\n" +
         element + "\n</mechanism>\n</diagram>\n";
}

std::string ErrorOf(const std::string& element) {
  return InputErrorOf([&] { LoadXml(WithElement(element)); });
}

TEST(BadInputTest, ContactNegativeStiffness) {
  const std::string e = ErrorOf(
      "<contact name='c' type='points_plane' body1='A' points='0 0 0' body2='Base0' normal='1 0 0' stiffness='-5'/>");
  EXPECT_THAT(e, StartsWith("test.xml:5: contact 'c': "));
  EXPECT_THAT(e, HasSubstr("the stiffness must be >= 0 (found -5)"));
}

TEST(BadInputTest, ContactNegativeFrictionCoefficient) {
  const std::string e = ErrorOf(
      "<contact name='c' type='circle_plane' body1='A' radius='0.1' circle_normal='0 0 1' body2='Base0' "
      "normal='1 0 0' stiffness='10' mu='-0.3'/>");
  EXPECT_THAT(e, StartsWith("test.xml:5: contact 'c': "));
  EXPECT_THAT(e, HasSubstr("the friction coefficient mu must be >= 0 (found -0.3)"));
}

TEST(BadInputTest, ContactStaticBelowDynamicFriction) {
  const std::string e = ErrorOf(
      "<contact name='c' type='points_plane' body1='A' points='0 0 0' body2='Base0' "
      "normal='1 0 0' stiffness='10' mu='0.4' mu_static='0.3'/>");
  EXPECT_THAT(e, HasSubstr("mu_static must not be below mu (static below dynamic friction) (found 0.3)"));
  EXPECT_THAT(ErrorOf("<contact name='c' type='points_plane' body1='A' points='0 0 0' body2='Base0' "
                      "normal='1 0 0' stiffness='10' mu='0.4' stribeck_velocity='0'/>"),
              HasSubstr("stribeck_velocity must be > 0"));
}

TEST(BadInputTest, ContactPlaneWithZeroNormal) {
  EXPECT_THAT(ErrorOf("<contact name='c' type='points_plane' body1='A' points='0 0 0' body2='Base0' normal='0 0 0'/>"),
              StartsWith("test.xml:5: contact 'c': the plane normal must be non-zero"));
  EXPECT_THAT(ErrorOf("<contact name='c' type='circle_plane' body1='A' radius='0.1' body2='Base0' normal='0 0 0'/>"),
              StartsWith("test.xml:5: contact 'c': the plane normal must be non-zero"));
}

TEST(BadInputTest, ContactPenetrationBoundNotPositive) {
  EXPECT_THAT(ErrorOf("<contact name='c' type='points_plane' body1='A' points='0 0 0' body2='Base0' normal='1 0 0' "
                      "max_penetration='0'/>"),
              StartsWith("test.xml:5: contact 'c': max_penetration must be > 0 (found 0)"));
}

TEST(BadInputTest, FrictionalNegativeFriction) {
  EXPECT_EQ(ErrorOf("<force name='f' type='frictional' body1='Base0' body2='A' point2='1 0 0'\n"
                    "       friction='-2' c='100'/>"),
            "test.xml:6: force 'f' attribute 'friction': the friction force must not be negative (found -2)");
}

TEST(BadInputTest, FrictionalStaticBelowDynamic) {
  EXPECT_EQ(ErrorOf("<force name='f' type='elastic_friction' body1='Base0' body2='A' point2='1 0 0' friction='2' "
                    "c='100' ratio='0.8'/>"),
            "test.xml:5: force 'f' attribute 'ratio': the ratio of static to dynamic friction must be at least 1 "
            "(static below dynamic friction) (found 0.8)");
}

TEST(BadInputTest, FrictionalNegativeStiffness) {
  EXPECT_EQ(ErrorOf("<force name='f' type='frictional' body1='Base0' body2='A' point2='1 0 0' friction='2' c='-100'/>"),
            "test.xml:5: force 'f' attribute 'c': the stiffness c must not be negative (found -100)");
}

TEST(BadInputTest, LinearLawNegativeStiffness) {
  EXPECT_EQ(ErrorOf("<joint_force name='s' dof='x' type='linear' c='-1000'/>"),
            "test.xml:5: joint_force 's' attribute 'c': the stiffness c must not be negative (found -1000)");
  EXPECT_EQ(ErrorOf("<force name='s' type='linear' body1='Base0' body2='A' point2='1 0 0' c='10' d='-1'/>"),
            "test.xml:5: force 's' attribute 'd': the damping d must not be negative (found -1)");
}

TEST(BadInputTest, BushingNegativeStiffness) {
  EXPECT_EQ(ErrorOf("<bushing name='b' body1='Base0' body2='A' c='100 -100 100'/>"),
            "test.xml:5: bushing 'b' attribute 'c': stiffness and damping must not be negative (found -100)");
}

TEST(BadInputTest, FrictionBlockStaticBelowDynamic) {
  const std::string e = InputErrorOf([] {
    LoadXml("<diagram>\n<blocks>\n"
            "<block type='friction_from_normal_force' name='f' mu_static='0.2' mu_dynamic='0.3'/>\n"
            "</blocks>\n</diagram>\n");
  });
  EXPECT_THAT(e, StartsWith("test.xml:3: block 'f' (friction_from_normal_force): "));
  EXPECT_THAT(e, HasSubstr("mu_static must not be below mu_dynamic"));
}

// <report>s (diagrams/FORMAT.md, "Reports").
std::string WithReport(const std::string& report) {
  return "<diagram>\n<blocks><block type='sine' name='s'/></blocks>\n<output>\n" + report +
         "\n</output>\n</diagram>\n";
}

TEST(BadInputTest, ReportOfAnUnknownSignal) {
  EXPECT_THAT(InputErrorOf([] { LoadXml(WithReport("<report peak='sin.y'/>")); }),
              StartsWith("test.xml:4: <report>: signal 'sin.y': no block named 'sin'"));
  EXPECT_THAT(InputErrorOf([] { LoadXml(WithReport("<report min='s.z'/>")); }),
              StartsWith("test.xml:4: <report>: signal 's.z': block 's' has no output 'z'"));
}

TEST(BadInputTest, ReportAsksForNoneOrTwoFigures) {
  EXPECT_THAT(InputErrorOf([] { LoadXml(WithReport("<report label='x'/>")); }),
              StartsWith("test.xml:4: <report> needs one of peak, min, peak_abs, mean, rms, integral, final, crossing "
                         "or period =\"signal\""));
  EXPECT_THAT(InputErrorOf([] { LoadXml(WithReport("<report peak='s.y' min='s.y'/>")); }),
              StartsWith("test.xml:4: <report> asks for 'peak' and 'min'; one figure per <report>"));
  EXPECT_THAT(InputErrorOf([] { LoadXml(WithReport("<report peak='s.y' index='1'/>")); }),
              StartsWith("test.xml:4: <report>: index 1 is not an element of 's.y' (width 1)"));
  EXPECT_THAT(InputErrorOf([] { LoadXml(WithReport("<report maximum='s.y'/>")); }),
              StartsWith("test.xml:4: <report> has no attribute 'maximum'"));
}

}  // namespace
}  // namespace mechflow::diagrams::bad_input_test
