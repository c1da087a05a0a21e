// Results files a tool can read (issue 15, item 4): a unit for every column
// (NAME.units.csv, and on the plot's axes), identifier names as the diagram
// writes them, and shortest round-trip numbers in the script's changes.

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

fs::path Dir(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(ResultsFilesTest, EveryColumnHasItsUnitAndThePlotAxesShowThem) {
  const fs::path dir = Dir("units");
  std::ofstream(dir / "d.xml")
      << "<diagram name='d'><identifiers><identifier name='Push' value='2' unit='kN'/></identifiers>"
         "<mechanism name='m' gravity='0 0 0'><body name='B' mass='1' inertia='1 1 1'/>"
         "<joint name='j' type='rotational' body1='Base0' body2='B' axis='0 0 1'/>"
         "<joint_force name='k' dof='j' type='linear' c='10'/>"
         "<sensor name='phi' kind='coordinate' dof='j'/><sensor name='w' kind='velocity' dof='j'/>"
         "<sensor name='moment' kind='element' element='k'/></mechanism>"
         "<blocks><block type='identifier' name='push' identifier='Push'/><block type='sine' name='s'/></blocks>"
         "<solver t_end='0.1'/><output interval='0.01' plot='d.png'>"
         "<log signal='m.phi' group='angle'/><log signal='m.w' group='rate [1/s]'/><log signal='m.moment'/>"
         "<log signal='push.y' group='push'/><log signal='s.y' group='sine'/>"
         "<log signal='s.y' label='scaled' unit='mm' group='scaled'/></output></diagram>";
  const auto run = testing::RunMechflow("run " + (dir / "d.xml").string() + " --out " + (dir / "out").string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(testing::ReadFile(dir / "out" / "d.units.csv"),
            "column,unit\ntime,s\nm.phi,rad\nm.w,rad/s\nm.moment,N m\npush.y,kN\ns.y,\nscaled,mm\n");
  const std::string script = testing::ReadFile(dir / "out" / "d.png.gp");
  EXPECT_THAT(script, HasSubstr("set ylabel 'angle [rad]'"));
  EXPECT_THAT(script, HasSubstr("set ylabel 'rate [1/s]'"));  // the group's own unit wins
  EXPECT_THAT(script, HasSubstr("set ylabel 'm.moment [N m]'"));
  EXPECT_THAT(script, HasSubstr("set ylabel 'push [kN]'"));
  EXPECT_THAT(script, HasSubstr("set ylabel 'sine'\n"));  // unknown: no brackets
  EXPECT_THAT(script, HasSubstr("set ylabel 'scaled [mm]'"));
}

TEST(ResultsFilesTest, SweepsWriteIdentifierNamesAsTheDiagramDoes) {
  const fs::path dir = Dir("spelling");
  std::ofstream(dir / "d.xml") << "<diagram name='d'><identifiers><identifier name='Gain_K' value='1'/></identifiers>"
                                  "<blocks><block type='gain' name='g' k='Gain_K'/><block type='integrator' name='i'/>"
                                  "</blocks><connections><connect from='g.y' to='i.u'/><connect from='i.y' to='g.u'/>"
                                  "</connections><solver t_end='0.1'/><output interval='0.05'>"
                                  "<log signal='i.y'/></output></diagram>";
  const auto run =
      testing::RunMechflow("sweep " + (dir / "d.xml").string() + " --vary gain_k=1,2 --out " + (dir / "out").string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_THAT(testing::ReadFile(dir / "out" / "d.sweep.csv"), HasSubstr("run,Gain_K,status"));
  EXPECT_TRUE(fs::exists(dir / "out" / "d.run1.Gain_K=1.csv"));
}

}  // namespace
}  // namespace mechflow
