// Units of identifiers are real: UDUNITS-2 reads them, values become SI when
// the diagram is loaded, and dimensions are checked where an attribute's is
// known (diagrams/units.h, diagrams/unit_check.h).

#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "diagrams/expression_dimension.h"
#include "diagrams/units.h"
#include "tests/test_util.h"

namespace mechflow::diagrams {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::IsEmpty;
using ::testing::StartsWith;
using mechflow::testing::InputErrorOf;
using mechflow::testing::LoadXml;

// The SI value of `value` given in `unit`, as a loaded diagram holds it.
double LoadedValue(const std::string& value, const std::string& unit) {
  const LoadedDiagram d = LoadXml("<diagram><identifiers><identifier name='q' value='" + value + "' unit='" + unit +
                                  "'/></identifiers><solver t_end='1'/></diagram>");
  return d.identifiers->Value("q");
}

TEST(UnitsTest, IdentifiersBecomeSiWhenLoaded) {
  const double pi = std::acos(-1.0);
  EXPECT_DOUBLE_EQ(LoadedValue("6", "deg"), 6 * pi / 180);
  EXPECT_DOUBLE_EQ(LoadedValue("200", "mm"), 0.2);
  EXPECT_DOUBLE_EQ(LoadedValue("30", "kN"), 30000);
  EXPECT_DOUBLE_EQ(LoadedValue("2", "N/mm"), 2000);
  EXPECT_DOUBLE_EQ(LoadedValue("60", "rpm"), 2 * pi);  // an angular speed in rad/s, not rev/s
  EXPECT_DOUBLE_EQ(LoadedValue("1", "rev"), 2 * pi);
  EXPECT_DOUBLE_EQ(LoadedValue("250", "g"), 0.25);     // gram
  EXPECT_DOUBLE_EQ(LoadedValue("3", "bar"), 3e5);
  EXPECT_DOUBLE_EQ(LoadedValue("2", "kN*m"), 2000);
  EXPECT_DOUBLE_EQ(LoadedValue("36", "km/h"), 10);
  EXPECT_DOUBLE_EQ(LoadedValue("7", "m"), 7);  // SI stays as written
}

TEST(UnitsTest, DimensionsCountTheRadianApart) {
  std::string error;
  const auto stiffness = ParseUnit("N/mm", &error);
  ASSERT_TRUE(stiffness) << error;
  EXPECT_EQ(stiffness->dimension.Text(), "kg s^-2");
  EXPECT_EQ(stiffness->dimension.Describe(), "a stiffness");
  const auto rotational = ParseUnit("N m/rad", &error), torque = ParseUnit("N m", &error);
  EXPECT_EQ(rotational->dimension.Describe(), "a rotational stiffness");
  EXPECT_TRUE(rotational->dimension.SameAs(torque->dimension));  // SI: the radian is 1
  EXPECT_EQ(ParseUnit("deg", &error)->dimension.Describe(), "an angle");
}

TEST(UnitsTest, UnknownAndOffsetUnitsAreBadInputAtTheirLine) {
  const auto error_of = [](const std::string& unit) {
    return InputErrorOf([&] {
      LoadXml("<diagram>\n<identifiers>\n<identifier name='q' value='1' unit='" + unit +
              "'/></identifiers><solver t_end='1'/></diagram>");
    });
  };
  EXPECT_THAT(error_of("furlongz"), StartsWith("test.xml:3: identifier 'q': unknown unit 'furlongz'"));
  EXPECT_THAT(error_of("degC"), AllOf(StartsWith("test.xml:3: identifier 'q': unit 'degC'"), HasSubstr("offset")));
  EXPECT_THAT(error_of("s since 1970-01-01"), HasSubstr("timestamp"));
}

TEST(UnitsTest, VariantsAndSetNumbersAreInTheIdentifiersUnit) {
  const std::string xml =
      "<diagram><identifiers><identifier name='L' value='200' unit='mm'/></identifiers>"
      "<variants name='v'><variant name='long'><set identifier='L' value='500'/></variant></variants>"
      "<solver t_end='1'/></diagram>";
  LoadOptions variant;
  variant.variants = {"long"};
  EXPECT_DOUBLE_EQ(LoadXml(xml, variant).identifiers->Value("L"), 0.5);
  LoadOptions set;
  set.overrides = {{"L", 300}};
  EXPECT_DOUBLE_EQ(LoadXml(xml, set).identifiers->Value("L"), 0.3);
}

// A body whose mass is an identifier of length, at the attribute's line and the identifier's.
TEST(UnitsTest, AnIdentifierOfAnotherDimensionIsBadInputNamingBothLines) {
  const std::string error = InputErrorOf([] {
    LoadXml("<diagram>\n<identifiers>\n<identifier name='L' value='200' unit='mm'/>\n</identifiers>\n"
            "<mechanism name='m'>\n<body name='B' mass='L' inertia='1 1 1'/>\n</mechanism>\n"
            "<solver t_end='1'/></diagram>");
  });
  EXPECT_THAT(error, StartsWith("test.xml:6: body 'B' attribute 'mass': 'L' is a length in mm (test.xml:3), used as "
                                "'mass' (kg)"));
  // a vector's component, and a joint's q0 by its type
  EXPECT_THAT(InputErrorOf([] {
                LoadXml("<diagram>\n<identifiers>\n<identifier name='m0' value='2' unit='kg'/>\n</identifiers>\n"
                        "<mechanism name='m'>\n<body name='B' mass='1' inertia='1 1 1'/>\n"
                        "<joint name='j' type='rotational' body1='Base0' body2='B' point1='0 m0 0' q0='0'/>\n"
                        "</mechanism>\n<solver t_end='1'/></diagram>");
              }),
              StartsWith("test.xml:7: joint 'j' attribute 'point1': 'm0' is a mass in kg (test.xml:3)"));
  EXPECT_THAT(InputErrorOf([] {
                LoadXml("<diagram>\n<identifiers>\n<identifier name='x0' value='2' unit='mm'/>\n</identifiers>\n"
                        "<mechanism name='m'>\n<body name='B' mass='1' inertia='1 1 1'/>\n"
                        "<joint name='j' type='rotational' body1='Base0' body2='B' q0='x0'/>\n"
                        "</mechanism>\n<solver t_end='1'/></diagram>");
              }),
              HasSubstr("'x0' is a length in mm (test.xml:3), used as 'q0' (rad)"));
  // an angle in degrees is an angle: no complaint, and its value is in rad
  const LoadedDiagram ok =
      LoadXml("<diagram>\n<identifiers>\n<identifier name='a' value='90' unit='deg'/>\n</identifiers>\n"
              "<mechanism name='m'>\n<body name='B' mass='1' inertia='1 1 1'/>\n"
              "<joint name='j' type='rotational' body1='Base0' body2='B' q0='a'/>\n"
              "</mechanism>\n<solver t_end='1'/></diagram>");
  EXPECT_THAT(ok.warnings, IsEmpty());
}

// A radian counts as 1, so rpm and Hz share a dimension; one given for the
// other is taken as its SI value (60 rpm as a frequency is 6.28 Hz): a
// warning says what it is taken as and what one turn a cycle would be.
TEST(UnitsTest, AnAngularRateForAFrequencyOrTheOtherWayIsAWarning) {
  const LoadedDiagram d = LoadXml(
      "<diagram>\n<identifiers>\n<identifier name='fr' value='60' unit='rpm'/>\n"
      "<identifier name='spin' value='1' unit='Hz'/>\n<identifier name='f' value='2' unit='Hz'/>\n"
      "<identifier name='w' value='90' unit='rpm'/>\n</identifiers>\n"
      "<mechanism name='m'>\n<body name='B' mass='1' inertia='1 1 1'/>\n"
      "<joint name='j' type='rotational' body1='Base0' body2='B' v0='spin'/>\n"
      "<body name='C' mass='1' inertia='1 1 1'/>\n"
      "<joint name='k' type='rotational' body1='Base0' body2='C' v0='w'/>\n</mechanism>\n"
      "<blocks>\n<block type='sine' name='s' frequency='fr'/>\n<block type='sine' name='t' frequency='f'/>\n"
      "</blocks>\n<solver t_end='1'/></diagram>");
  ASSERT_EQ(d.warnings.size(), 2u);  // w (rpm as rad/s) and f (Hz as Hz) are what they say
  EXPECT_THAT(d.warnings[0], StartsWith("test.xml:10: warning: joint 'j' attribute 'v0': 'spin' is 1 Hz, a "
                                        "frequency, used as 'v0' (rad/s): taken as 1 rad/s, not the 6.283185307"));
  EXPECT_THAT(d.warnings[1], StartsWith("test.xml:15: warning: block 's' parameter 'frequency': 'fr' is 60 rpm, an "
                                        "angular rate (6.283185307 rad/s), used as 'frequency' (Hz): taken as "
                                        "6.283185307 Hz, not the 1 Hz of one turn a cycle"));
  // a block parameter with a unit is checked as an element attribute is: a time is no frequency
  EXPECT_THAT(InputErrorOf([] {
                LoadXml("<diagram>\n<identifiers>\n<identifier name='period' value='2' unit='s'/>\n</identifiers>\n"
                        "<blocks><block type='sine' name='s' frequency='period'/></blocks>\n<solver t_end='1'/></diagram>");
              }),
              StartsWith("test.xml:5: block 's' parameter 'frequency': 'period' is a time in s (test.xml:3), used as "
                         "'frequency' (Hz)"));
}

TEST(UnitsTest, ExpressionsPropagateDimensions) {
  std::string error;
  const auto of = [&](const std::string& name) -> std::optional<Dimension> {
    if (name == "f") return ParseUnit("Hz", &error)->dimension;
    if (name == "m") return ParseUnit("kg", &error)->dimension;
    if (name == "L") return ParseUnit("mm", &error)->dimension;
    return std::nullopt;
  };
  EXPECT_EQ(InferDimension("4*pi^2*f^2*m", of).dimension.Describe(), "a stiffness");
  EXPECT_EQ(InferDimension("2*0.3*sqrt(m*4*pi^2*f^2*m)", of).dimension.Describe(), "a damping");
  EXPECT_EQ(InferDimension("(L - 0.005)/2", of).dimension.Describe(), "a length");  // a number takes the other's
  EXPECT_FALSE(InferDimension("beta*m", of).known);                                // beta has no unit
  EXPECT_FALSE(InferDimension("x > 0 and m or 0", of).known);
  EXPECT_THAT(InferDimension("L + m", of).conflict, HasSubstr("adds a length (m) and a mass (kg)"));
}

TEST(UnitsTest, AnExpressionThatDisagreesWithItsUnitIsAWarningNamingItsLine) {
  const LoadedDiagram d =
      LoadXml("<diagram>\n<identifiers>\n<identifier name='m' value='2' unit='kg'/>\n"
              "<identifier name='f' value='50' unit='Hz'/>\n"
              "<identifier name='c' value='4*pi^2*f^2*m' unit='N/mm'/>\n"     // right: a stiffness
              "<identifier name='d' value='2*0.3*sqrt(m*c)' unit='N/m'/>\n"  // wrong: a damping
              "</identifiers><solver t_end='1'/></diagram>");
  ASSERT_EQ(d.warnings.size(), 1u);
  EXPECT_THAT(d.warnings[0], StartsWith("test.xml:6: warning: identifier 'd' = '2*0.3*sqrt(m*c)' is a damping"));
  EXPECT_THAT(d.warnings[0], HasSubstr("but its unit is N/m (a stiffness)"));
  // the expression computes in SI: c is 4 pi^2 50^2 2 N/m whatever unit shows it
  EXPECT_DOUBLE_EQ(d.identifiers->Value("c"), 4 * std::acos(-1.0) * std::acos(-1.0) * 2500 * 2);
}

}  // namespace
}  // namespace mechflow::diagrams
