// <xy> panels: a logged column against another in the
// run's plot -- the script draws exactly the columns named, from the results
// written beside it; bad input exits 2 at its line.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/cli/mechflow_command.h"

namespace mechflow {
namespace {

using ::testing::HasSubstr;
using testing::ReadFile;
using testing::RunMechflow;
namespace fs = std::filesystem;

int ColumnNumber(const std::string& csv, const std::string& name) {  // 1-based, as gnuplot counts
  std::stringstream header(csv.substr(0, csv.find('\n')));
  int n = 0;
  for (std::string cell; std::getline(header, cell, ',');) {
    ++n;
    if (cell == name) return n;
  }
  return -1;
}

TEST(XYPlotTest, HysteresisAndPathsDrawTheNamedColumns) {
  const fs::path out = fs::path(::testing::TempDir()) / "xy_plot";
  for (const auto& [example, curves] :
       std::vector<std::pair<std::string, std::vector<std::pair<std::string, std::string>>>>{
           {"elast_friction2", {{"m.x", "m.force"}}},
           {"math_game", {{"g.target_y", "g.target_z"}, {"g.pursuer_y", "g.pursuer_z"}}}}) {
    const auto run = RunMechflow("run " + std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/" + example +
                                 ".xml --out " + out.string());
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const std::string script = ReadFile(out / (example + ".png.gp"));
    // a long run's x-y panels draw its extreme rows, from a file of their own
    const std::string xy_rows = example + ".png.xy.csv";
    const std::string csv =
        ReadFile(out / (script.find("'" + xy_rows + "'") != std::string::npos ? xy_rows : example + ".csv"));
    for (const auto& [x, y] : curves) {
      const std::string using_ = "using " + std::to_string(ColumnNumber(csv, x)) + ":" +
                                 std::to_string(ColumnNumber(csv, y)) + " every ::1 with lines";
      EXPECT_THAT(script, HasSubstr(using_)) << example;
      EXPECT_THAT(script, HasSubstr("title '" + y + " : " + x + "'")) << example;
    }
    EXPECT_GT(fs::file_size(out / (example + ".png")), 1000u);
  }
}

TEST(XYPlotTest, BadPanelsExit2) {
  const fs::path dir = fs::path(::testing::TempDir()) / "xy_bad";
  fs::create_directories(dir);
  const auto diagram = [&](const std::string& output_attributes, const std::string& xy) {
    std::ofstream(dir / "d.xml") << "<diagram name='d'>\n<blocks><block type='sine' name='s' amplitude='1' "
                                    "frequency='5'/></blocks>\n<solver t_end='1'/>\n<output interval='0.01' "
                                 << output_attributes << "><log signal='s.y'/>\n" << xy << "</output>\n</diagram>\n";
    return RunMechflow("run " + (dir / "d.xml").string() + " --out " + dir.string());
  };
  auto outcome = diagram("plot='d.png'", "<xy curves='time:s.x'/>");
  EXPECT_EQ(outcome.exit_code, 2);
  EXPECT_THAT(outcome.err, HasSubstr("d.xml:5: <xy>: 's.x' is not a logged column (did you mean 's.y'?)"));
  outcome = diagram("plot='d.png'", "<xy curves='time'/>");
  EXPECT_EQ(outcome.exit_code, 2);
  EXPECT_THAT(outcome.err, HasSubstr("curves are X:Y pairs"));
  outcome = diagram("", "<xy curves='time:s.y'/>");
  EXPECT_EQ(outcome.exit_code, 2);
  EXPECT_THAT(outcome.err, HasSubstr("d.xml:5: <xy> is a panel of the plot, and there is none"));
}

}  // namespace
}  // namespace mechflow
