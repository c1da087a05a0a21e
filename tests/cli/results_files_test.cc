// Results files another tool can read without help: a unit for every column
// (NAME.units.csv, and on the plot's axes), identifier names as the diagram
// writes them, and shortest round-trip numbers in the script's changes.

#include <charconv>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "blocks/outputs/csv.h"
#include "cli/gnuplot_text.h"
#include "cli/output_folder.h"
#include "cli/plot.h"
#include "cli/results_file.h"
#include "tests/cli/mechflow_command.h"
#include "tests/test_util.h"

namespace mechflow::results_files_test {  // names of its own: the files of its folder are compiled together
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

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

// t_start + k * interval rounds (0.1 + 2 * 0.01 = 0.12000000000000001): the
// rows are taken at the decimal times, which the CSV writes in their shortest
// form; every number in the file reads back to the double the run computed.
TEST(ResultsFilesTest, TimesAreTheirDecimalsAndEveryNumberReadsBackBitwise) {
  const auto run = testing::RunDescription(diagrams::ReadDiagramText(
      "<diagram name='d'><blocks><block type='sine' name='s' amplitude='1/3' frequency='7'/>"
      "<block type='gain' name='g' k='-1'/><block type='constant' name='zero' value='0'/></blocks>"
      "<connections><connect from='zero.y' to='g.u'/></connections>"
      "<solver t_start='0.1' t_end='1'/><output interval='0.01'><log signal='s.y'/><log signal='g.y'/></output>"
      "</diagram>", "test.xml"));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const blocks::Results& results = run.sim->results();
  ASSERT_EQ(results.num_rows(), 91);
  const fs::path dir = Dir("decimal_times");
  {
    cli::ResultsFile file(cli::OutputFolder(dir.string()), "d.csv", results.columns());
    for (int r = 0; r < results.num_rows(); ++r) {
      std::vector<double> row;
      for (int c = 0; c < results.num_columns(); ++c) row.push_back(results.at(r, c));
      file.WriteRow(row.data(), static_cast<int>(row.size()));
    }
    ASSERT_EQ(file.Close(), "");
  }
  std::istringstream csv(testing::ReadFile(dir / "d.csv"));
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "time,s.y,g.y");
  for (int r = 0; std::getline(csv, line); ++r) {
    std::istringstream fields(line);
    std::string field;
    for (int c = 0; std::getline(fields, field, ','); ++c) {
      if (c == 0) {
        EXPECT_EQ(field, blocks::CsvNumber((10 + r) / 100.0)) << "row " << r;  // "0.13", "0.47"
      }
      double back = 0.0;
      ASSERT_EQ(std::from_chars(field.data(), field.data() + field.size(), back).ptr, field.data() + field.size());
      const double value = results.at(r, c);
      if (value == 0.0) {
        EXPECT_EQ(back, 0.0);  // -0 is written 0 (g.y = -1 * 0)
      } else {
        EXPECT_EQ(std::memcmp(&back, &value, sizeof back), 0) << field << " at row " << r << ", column " << c;
      }
    }
  }
}

// A negative zero (-1 * 0) shows as 0 in the terminal's table and figures.
TEST(ResultsFilesTest, TheTerminalShowsNoNegativeZero) {
  const fs::path dir = Dir("negative_zero");
  std::ofstream(dir / "d.xml") << "<diagram name='d'><blocks><block type='constant' name='zero' value='0'/>"
                                  "<block type='gain' name='g' k='-1'/></blocks>"
                                  "<connections><connect from='zero.y' to='g.u'/></connections>"
                                  "<solver t_end='1'/><output interval='0.1'><log signal='g.y'/>"
                                  "<report peak='g.y' label='peak'/></output></diagram>";
  const auto run = testing::RunMechflow("run " + (dir / "d.xml").string() + " --out " + (dir / "out").string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_THAT(run.out, HasSubstr("peak: 0 at t = 0 s"));
  EXPECT_THAT(run.out, HasSubstr("g.y                 0           0              0           0\n"));
  EXPECT_FALSE(std::regex_search(run.out, std::regex("(^|[ =])-0([ ,]|$)", std::regex::multiline))) << run.out;
}

TEST(ResultsFilesTest, LegendsShowSixDigitsUnlessMoreTellTheValuesApart) {
  EXPECT_EQ(cli::LegendNumbers({0.0316227766016838, 0.1, 500000, 1e-5, -0.0}),
            (std::vector<std::string>{"0.0316228", "0.1", "500000", "1e-05", "0"}));
  EXPECT_EQ(cli::LegendNumbers({1, 1.0000001, 1.0000002}),
            (std::vector<std::string>{"1", "1.0000001", "1.0000002"}));
  // doubles one unit in the last place apart: all 17 digits
  EXPECT_EQ(cli::LegendNumbers({0.1, 0.10000000000000002}),
            (std::vector<std::string>{"0.10000000000000001", "0.10000000000000002"}));
}

// 15 runs in one panel: gnuplot's own order repeats 8 colours; every curve
// of the overlay gets a colour and dash type of its own, its legend the
// values to 6 digits, or as many as tell the runs apart.
TEST(ResultsFilesTest, ASweepsCurvesLookDifferentAndTheirLegendsReadShort) {
  const fs::path dir = Dir("sweep_legend");
  std::ofstream(dir / "d.xml") << "<diagram name='d'><identifiers><identifier name='K' value='1'/>"
                                  "<identifier name='c' value='1'/></identifiers>"
                                  "<blocks><block type='gain' name='g' k='-K*c'/><block type='integrator' name='i' "
                                  "initial='1'/></blocks><connections><connect from='g.y' to='i.u'/>"
                                  "<connect from='i.y' to='g.u'/></connections><solver t_end='0.1'/>"
                                  "<output interval='0.05'><log signal='i.y'/></output></diagram>";
  const auto run = testing::RunMechflow("sweep " + (dir / "d.xml").string() +
                                        " --vary K=0.01:1:5:log --vary c=1,1.0000001,1.0000002 --quiet --out " +
                                        (dir / "out").string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string script = testing::ReadFile(dir / "out" / "d.sweep.png.gp");
  EXPECT_THAT(script, HasSubstr("title 'K=0.0316228, c=1.0000001'"));
  EXPECT_THAT(script, HasSubstr("title 'K=1, c=1'"));
  EXPECT_THAT(script, Not(HasSubstr("title 'K=0.0316227766")));  // file names keep every digit
  std::set<std::string> looks;
  int curves = 0;
  const std::regex look("with lines lw 1.5 (lc rgb '#[0-9a-f]{6}' dt [^ ]+) title");
  for (auto it = std::sregex_iterator(script.begin(), script.end(), look); it != std::sregex_iterator(); ++it, ++curves)
    looks.insert((*it)[1]);
  EXPECT_EQ(curves, 15);
  EXPECT_EQ(looks.size(), 15u);
}

TEST(ResultsFilesTest, FiftyCurvesLookDifferent) {
  std::set<std::string> looks;
  for (int i = 0; i < 50; ++i) looks.insert(cli::CurveStyle(i));
  EXPECT_EQ(looks.size(), 50u);
}

}  // namespace
}  // namespace mechflow::results_files_test
