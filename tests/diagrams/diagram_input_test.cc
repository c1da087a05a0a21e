// A diagram's top-level <input>: a held value, a signal source named after
// it, starting from `start` in its unit; misuse is refused naming file:line.

#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/test_util.h"

namespace mechflow {
namespace {

using ::testing::HasSubstr;
using testing::InputErrorOf;
using testing::LoadXml;
using testing::RunXml;

std::string WithInput(const std::string& input, const std::string& connections = R"(<connect from="F" to="x"/>)") {
  return "<diagram name=\"d\">\n  " + input +
         "\n  <blocks><block type=\"integrator\" name=\"x\"/></blocks>\n  <connections>" + connections +
         "</connections>\n  <solver t_end=\"1\"/>\n  <output interval=\"0.5\"><log signal=\"x\"/></output>\n</diagram>";
}

TEST(DiagramInputTest, HoldsItsStartInSiAndFeedsItsConnections) {
  const auto run = RunXml(WithInput(R"(<input name="F" unit="kN" start="2*3" comment="push"/>)"));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  EXPECT_NEAR(run.Column("x.y").back(), 6000.0, 1e-6);  // 6 kN integrated over 1 s
  ASSERT_EQ(run.loaded.inputs.size(), 1u);
  const diagrams::DiagramInput& in = run.loaded.inputs[0];
  EXPECT_EQ(in.name, "F");
  EXPECT_EQ(in.unit, "kN");
  EXPECT_EQ(in.to_si, 1000.0);
  EXPECT_EQ(in.start, 6000.0);
  EXPECT_EQ(in.comment, "push");
  EXPECT_EQ(in.origin, "test.xml:2");
  EXPECT_EQ(run.loaded.diagram->block(in.block).name(), "F");
}

TEST(DiagramInputTest, MisuseIsRefusedNamingFileAndLine) {
  EXPECT_THAT(InputErrorOf([] { LoadXml(WithInput(R"(<input name="a.b"/>)")); }),
              HasSubstr("test.xml:2: input 'a.b': the name must be letters, digits and '_'"));
  EXPECT_THAT(InputErrorOf([] { LoadXml(WithInput(R"(<input name="F" unit="furlong/bogus"/>)")); }),
              HasSubstr("test.xml:2: input 'F': unknown unit"));
  EXPECT_THAT(InputErrorOf([] { LoadXml(WithInput(R"(<input name="F" width="3"/>)")); }),
              HasSubstr("test.xml:2"));
  EXPECT_THAT(InputErrorOf([] { LoadXml(WithInput(R"(<input name="x"/>)", "")); }), HasSubstr("used twice"));
  // an input has no input port: nothing drives it
  EXPECT_THAT(InputErrorOf([] {
                LoadXml(WithInput(R"(<input name="F"/>)", R"(<connect from="F" to="x"/><connect from="x" to="F"/>)"));
              }),
              HasSubstr("test.xml:"));
  EXPECT_THAT(InputErrorOf([] { LoadXml(WithInput(R"(<input name="F" start="q"/>)")); }), HasSubstr("test.xml:2"));
}

}  // namespace
}  // namespace mechflow
