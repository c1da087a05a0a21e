// An identifier computed from a mechanism's <input> follows the input in the
// mechanism's forces (diagrams/follow_inputs.h): a unit mass at rest pushed
// by F = k u, where u steps from 0 to 2 at t = 0.5 s, is at z = k (t - 0.5)^2
// at t = 1 s. Before, F kept its load value (0) and the mass never moved.

#include "diagrams/follow_inputs.h"

#include <filesystem>
#include <fstream>
#include <tuple>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/test_util.h"

namespace mechflow::diagrams {
namespace {

using ::testing::HasSubstr;

std::string Pushed(const std::string& identifiers, const std::string& force) {
  return "<diagram>\n<identifiers><identifier name='u' value='0' unit='N'/>" + identifiers +
         "</identifiers>\n<mechanism name='m' gravity='0 0 0'>\n<input name='u'/>\n"
         "<body name='B' mass='1' inertia='1 1 1'/>\n"
         "<joint name='j' type='translational' body1='Base0' body2='B' axis='0 0 1'/>\n"
         "<applied_force name='push' body='B' force='0 0 " + force + "'/>\n"
         "<sensor name='z' kind='coordinate' dof='j'/>\n</mechanism>\n"
         "<blocks><block type='step' name='s' time='0.5' after='2'/></blocks>\n"
         "<connections><connect from='s.y' to='m.u'/></connections>\n"
         "<solver t_end='1' rtol='1e-10' atol='1e-12'/><output interval='0.5'><log signal='m.z'/></output>\n"
         "</diagram>\n";
}

TEST(FollowInputsTest, AnIdentifierOfAnInputFollowsItInAForce) {
  for (const auto& [identifiers, force, k] :
       {std::tuple<std::string, std::string, double>{"", "u", 1.0},
        {"<identifier name='F' value='3*u'/>", "F", 3.0},
        {"<identifier name='F' value='3*u'/><identifier name='G' value='F/2+0*u'/>", "G", 1.5}}) {
    const auto run = testing::RunXml(Pushed(identifiers, force));
    EXPECT_NEAR(run.Column("m.z").back(), k * 0.25, 1e-8) << force;
  }
}

TEST(FollowInputsTest, APartsParameterGivenTheInputFollowsIt) {
  const std::filesystem::path folder = std::filesystem::temp_directory_path() / "mechflow_follow_inputs_test";
  std::filesystem::create_directories(folder);
  std::ofstream(folder / "push.xml") << "<part name='push'>\n<parameter name='F' unit='N'/>\n<attach name='target'/>\n"
                                        "<applied_force name='f' body='target' force='0 0 F'/>\n</part>\n";
  std::string xml = Pushed("", "0");
  xml.replace(xml.find("<sensor"), 0,
              "<include part='push.xml' name='p' attach='target=B'><param name='F' value='2*u'/></include>\n");
  const auto run = testing::RunDescription(ReadDiagramText(xml, (folder / "main.xml").string()));
  EXPECT_NEAR(run.Column("m.z").back(), 2 * 0.25, 1e-8);
}

TEST(FollowInputsTest, AnAttributeFixedAtBuildRefusesAnIdentifierOfAnInput) {
  std::string xml = Pushed("<identifier name='M' value='1+u'/>", "u");
  xml.replace(xml.find("mass='1'"), 8, "mass='M'");
  EXPECT_THAT(testing::InputErrorOf([&] { testing::LoadXml(xml); }), HasSubstr("uses the input 'u'"));
}

}  // namespace
}  // namespace mechflow::diagrams
