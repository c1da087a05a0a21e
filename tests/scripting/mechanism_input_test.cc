// A mechanism <input> (an identifier a signal feeds) seen from a control
// script and from a time function (what a script sets must reach the
// mechanism or be refused): no silent no-op --
// sim:get reads the value the mechanism receives, sim:set is refused with
// what to do instead, and a tt/rt expression naming an input is refused.
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/test_util.h"

namespace mechflow {
namespace {

using ::testing::HasSubstr;

// LeafSpring (the friction force Ffr comes from a block) with a script.
std::string LeafSpringWithScript(const std::string& script) {
  std::string xml = testing::ReadExample("leaf_spring.xml");
  xml.insert(xml.find("<solver"), "<script>" + script + "</script>\n  ");
  return xml;
}

TEST(MechanismInputTest, GetReadsWhatTheMechanismReceives) {
  // the script checks what it reads against the signal feeding the input,
  // at every row
  const auto run = testing::RunXml(LeafSpringWithScript(
      "function step(sim) local a, b = sim:get('Ffr'), sim:get('friction_force.sliding') "
      "if a ~= b then error('Ffr reads ' .. a .. ', the mechanism receives ' .. b) end end"));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  double largest = 0;
  for (double f : run.Column("limit Ffr")) largest = std::max(largest, f);
  EXPECT_GT(largest, 1.0);  // the friction was not zero, so the check meant something
}

TEST(MechanismInputTest, SetOfAnInputIsRefusedSayingWhy) {
  const auto run = testing::RunXml(LeafSpringWithScript("function step(sim) sim:set('Ffr', 5) end"));
  EXPECT_FALSE(run.outcome.ok);
  EXPECT_THAT(run.outcome.failure, HasSubstr("'Ffr' is a mechanism input fed by a signal (m.Ffr <- friction_force.sliding)"));
  EXPECT_THAT(run.outcome.failure, HasSubstr("set what that signal is made from instead"));
}

TEST(MechanismInputTest, ATimeFunctionNamingAnInputIsRefused) {
  const std::string message = testing::InputErrorOf([] {
    testing::LoadXml(
        "<diagram><identifiers><identifier name='u' value='0'/></identifiers>"
        "<mechanism name='m' gravity='0 0 0'><input name='u'/><body name='B' mass='1' inertia='1 1 1'/>"
        "<joint name='j' type='generalized' body1='Base0' body2='B'><et type='tt' axis='1 0 0' value='u*t'/></joint>"
        "</mechanism><blocks><block type='constant' name='c' value='1'/></blocks>"
        "<connections><connect from='c.y' to='m.u'/></connections><solver t_end='1'/></diagram>");
  });
  EXPECT_THAT(message, HasSubstr("'value' names an <input> of this mechanism"));
  EXPECT_THAT(message, HasSubstr("drive the motion by a signal instead (signal=\"NAME\", fed by a motion block)"));
}

}  // namespace
}  // namespace mechflow
