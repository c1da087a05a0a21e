// `unit=` is real on the command line: an unknown unit or a dimension that
// does not fit exits 2 naming the lines, a unit that disagrees with its
// expression is a warning, a <log unit> converts its column, and
// `mechflow check` shows each identifier in its own unit and in SI.

#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/cli/mechflow_command.h"

namespace mechflow::units_command_test {  // names of its own: the files of its folder are compiled together
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

// d.xml in a fresh folder: identifiers on lines 3.., a pendulum-free body.
fs::path Write(const std::string& name, const std::string& identifiers, const std::string& rest) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("units_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "d.xml") << "<diagram name='d'>\n<identifiers>\n" << identifiers << "</identifiers>\n"
                               << rest << "</diagram>\n";
  return dir;
}

TEST(UnitsCommandTest, AnUnknownUnitExits2AtItsLine) {
  const fs::path dir = Write("unknown", "<identifier name='q0' value='6' unit='degs'/>\n", "<solver t_end='1'/>\n");
  const auto run = testing::RunMechflow("run " + (dir / "d.xml").string() + " --out " + (dir / "out").string());
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("d.xml:3: identifier 'q0': unknown unit 'degs'"));
}

TEST(UnitsCommandTest, ALengthUsedAsAMassExits2NamingBothLines) {
  const fs::path dir = Write("mismatch", "<identifier name='L' value='200' unit='mm'/>\n",
                             "<mechanism name='m'>\n<body name='B' mass='L' inertia='1 1 1'/>\n</mechanism>\n"
                             "<solver t_end='1'/>\n");
  const auto run = testing::RunMechflow("check " + (dir / "d.xml").string());
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("d.xml:6: body 'B' attribute 'mass': 'L' is a length in mm (" +
                                 (dir / "d.xml").string() + ":3), used as 'mass' (kg)"));
}

TEST(UnitsCommandTest, CheckShowsOwnUnitAndSiAndWarnsOfAUnitTheExpressionDisagreesWith) {
  const fs::path dir = Write("check",
                             "<identifier name='q0' value='6' unit='deg'/>\n"
                             "<identifier name='m' value='2' unit='kg'/>\n"
                             "<identifier name='w' value='4*m' unit='rad/s'/>\n",
                             "<solver t_end='1'/>\n");
  const auto run = testing::RunMechflow("check " + (dir / "d.xml").string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_THAT(run.out, HasSubstr("  q0 = 6 deg = 0.1047197551 rad\n"));
  EXPECT_THAT(run.out, HasSubstr("  m = 2 kg\n"));
  EXPECT_THAT(run.out, HasSubstr((dir / "d.xml").string() + ":5: warning: identifier 'w' = '4*m' is a mass (kg)"));
  EXPECT_THAT(run.out, HasSubstr(": ok (1 warning)"));
}

TEST(UnitsCommandTest, ALogUnitConvertsItsColumnAndSaysSo) {
  const fs::path dir = Write("log", "<identifier name='a' value='90' unit='deg'/>\n",
                             "<blocks><block type='identifier' name='angle' identifier='a'/>"
                             "<block type='constant' name='c' value='0.25'/></blocks>\n"
                             "<solver t_end='1'/>\n<output interval='0.5' plot='d.png'>"
                             "<log signal='angle.y' label='in_rad' unit='rad'/>"
                             "<log signal='angle.y' label='own'/>"
                             "<log signal='c.y' label='in_mm' unit='mm' group='length'/></output>\n");
  const auto run = testing::RunMechflow("run " + (dir / "d.xml").string() + " --out " + (dir / "out").string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string csv = testing::ReadFile(dir / "out" / "d.csv");
  EXPECT_THAT(csv, HasSubstr("time,in_rad,own,in_mm\n0,1.5707963267948966,90,250\n"));
  EXPECT_EQ(testing::ReadFile(dir / "out" / "d.units.csv"), "column,unit\ntime,s\nin_rad,rad\nown,deg\nin_mm,mm\n");
  EXPECT_THAT(testing::ReadFile(dir / "out" / "d.png.gp"), HasSubstr("set ylabel 'length [mm]'"));
  // a force cannot be shown in degrees
  const fs::path bad = Write("log_bad", "",
                             "<mechanism name='m'>\n<body name='B' mass='1' inertia='1 1 1'/>\n"
                             "<joint name='j' type='translational' body1='Base0' body2='B'/>\n"
                             "<sensor name='F' kind='reaction_force' joint='j'/>\n</mechanism>\n"
                             "<solver t_end='1'/>\n<output>\n<log signal='m.F' unit='deg'/></output>\n");
  const auto refused = testing::RunMechflow("run " + (bad / "d.xml").string() + " --out " + (bad / "out").string());
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_THAT(refused.err, HasSubstr("d.xml:11: <log> of 'm.F': the signal is a force (N), which cannot be shown in "
                                     "deg (an angle)"));
}

TEST(UnitsCommandTest, AReportUnitConvertsItsFigure) {
  const fs::path dir = Write("report", "",
                             "<blocks><block type='constant' name='c' value='0.25'/></blocks>\n"
                             "<solver t_end='1'/>\n<output interval='0.5'><log signal='c.y'/>"
                             "<report final='c.y' label='length' unit='mm'/></output>\n");
  const auto run = testing::RunMechflow("run " + (dir / "d.xml").string() + " --out " + (dir / "out").string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_THAT(run.out, HasSubstr("length: 250 mm"));
  EXPECT_THAT(testing::ReadFile(dir / "out" / "d.report.csv"), HasSubstr("length,final,c.y,250,mm,"));
  const fs::path bad = Write("report_bad", "",
                             "<blocks><block type='constant' name='c' value='1'/></blocks>\n<solver t_end='1'/>\n"
                             "<output><report period='c.y' level='0' unit='mm'/></output>\n");
  const auto refused = testing::RunMechflow("run " + (bad / "d.xml").string() + " --out " + (bad / "out").string());
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_THAT(refused.err, HasSubstr("d.xml:6: <report> of 'c.y': its period is a time (s), which cannot be shown "
                                     "in mm (a length)"));
}

}  // namespace
}  // namespace mechflow::units_command_test
