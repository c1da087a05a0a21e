// Output budgets: each file a run writes is estimated before the run and
// refused past --max-output (default 1 GiB per file), and a results file
// that outgrows its estimate stops at the budget with its rows kept.

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli/arguments.h"
#include "cli/output_budget.h"
#include "cli/output_folder.h"
#include "cli/results_file.h"
#include "tests/cli/mechflow_command.h"

namespace mechflow {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

fs::path Dir(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("output_budget_" + std::to_string(getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

const std::string kDampingRatio = std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/damping_ratio.xml";

TEST(OutputBudgetTest, SizesTakeBinarySuffixes) {
  EXPECT_EQ(cli::ParseByteSize("100", "--max-output"), 100u);
  EXPECT_EQ(cli::ParseByteSize("512K", "--max-output"), 512u << 10);
  EXPECT_EQ(cli::ParseByteSize("1.5k", "--max-output"), 1536u);
  EXPECT_EQ(cli::ParseByteSize("8G", "--max-output"), std::uint64_t{8} << 30);
  EXPECT_EQ(cli::ParseByteSize("2T", "--max-output"), std::uint64_t{2} << 40);
  for (const char* bad : {"", "G", "8X", "8GB", "-1", "0", "0.5", "nan", "inf", "1e9", " 8G", "8G "})
    EXPECT_THROW(cli::ParseByteSize(bad, "--max-output"), cli::UsageError) << bad;
}

TEST(OutputBudgetTest, ARunPastTheBudgetIsRefusedBeforeItStarts) {
  const fs::path dir = Dir("refused");
  // 10^8 rows of 3 columns: about 5.6 GiB, refused at once (the run would take many minutes)
  const auto big = testing::RunMechflow("run " + kDampingRatio + " --t-end 99999 --interval 1e-3 --out " +
                                        (dir / "out").string());
  EXPECT_EQ(big.exit_code, 2) << big.out << big.err;
  EXPECT_THAT(big.err, HasSubstr("damping_ratio.csv would be about 5.59 GiB (99999001 rows x 3 columns"));
  EXPECT_THAT(big.err, HasSubstr("past the budget of 1 GiB per output file"));
  EXPECT_THAT(big.err, HasSubstr("raise the output interval, shorten t_end, log fewer signals, or raise the budget with "
                                 "--max-output 8G"));
  EXPECT_FALSE(fs::exists(dir / "out" / "damping_ratio.csv"));  // nothing made, nothing truncated

  // the default run, 2001 rows x 3 columns (about 117 KiB): a smaller budget refuses it, a larger one lets it run
  const auto small = testing::RunMechflow("run " + kDampingRatio + " --max-output 100K --out " + (dir / "out").string());
  EXPECT_EQ(small.exit_code, 2) << small.err;
  EXPECT_THAT(small.err, HasSubstr("2001 rows x 3 columns"));
  EXPECT_THAT(small.err, HasSubstr("past the budget of 100 KiB"));
  const auto raised = testing::RunMechflow("run " + kDampingRatio + " --max-output=1M --out " + (dir / "out").string());
  EXPECT_EQ(raised.exit_code, 0) << raised.err;

  // the animation, estimated from its frames, bodies and meshes
  const auto animated = testing::RunMechflow("run " + kDampingRatio + " --animate --max-output 300K --out " +
                                             (dir / "out").string());
  EXPECT_EQ(animated.exit_code, 2) << animated.err;
  EXPECT_THAT(animated.err, HasSubstr("damping_ratio.html would be about"));
  EXPECT_THAT(animated.err, HasSubstr("frames x 1 bodies"));
  EXPECT_THAT(animated.err, HasSubstr("a plot of 2001 points x 3 numbers"));  // the plot's signals at every row
  EXPECT_THAT(animated.err, HasSubstr("--no-animate"));
}

TEST(OutputBudgetTest, EverySweepRunIsEstimated) {
  const fs::path dir = Dir("sweep");
  const auto sweep = testing::RunMechflow("sweep " + kDampingRatio + " --vary beta=0.1,0.2 --t-end 99999 --interval 1e-3 "
                                          "--out " + (dir / "out").string());
  EXPECT_EQ(sweep.exit_code, 2) << sweep.out << sweep.err;
  EXPECT_THAT(sweep.err, HasSubstr("damping_ratio.run1.beta=0.1.csv would be about 5.59 GiB"));
  EXPECT_THAT(sweep.err, HasSubstr("--max-output 8G"));
  const auto options = testing::RunMechflow("sweep " + kDampingRatio + " --vary beta=0.1 --max-output 8Q");
  EXPECT_EQ(options.exit_code, 2);
  EXPECT_THAT(options.err, HasSubstr("--max-output: '8Q' is not a size"));
}

// A results file that outgrows its estimate (rows at events, longer
// numbers) stops before the row that would pass the budget: whole rows, a
// message, and the run ends (exit 1).
TEST(OutputBudgetTest, AResultsFileStopsAtItsBudgetWithWholeRows) {
  const fs::path dir = Dir("stop");
  const cli::OutputFolder folder(dir.string());
  cli::ResultsFile file(folder, "r.csv", {"time", "x"});
  file.SetByteLimit(1000);
  int offered = 0;
  for (; offered < 1000 && file.stopped().empty(); ++offered) {
    const double row[2] = {offered * 0.1, -1.0 / (offered + 3)};
    file.WriteRow(row, 2);
  }
  EXPECT_THAT(file.stopped(), HasSubstr("r.csv' reached the output budget of 1000 bytes after"));
  EXPECT_THAT(file.stopped(), HasSubstr("the rows up to there are written"));
  EXPECT_EQ(file.Close(), "");
  const std::string text = testing::ReadFile(dir / "r.csv");
  EXPECT_LE(text.size(), 1000u);
  EXPECT_GT(text.size(), 900u);  // filled up to the budget
  EXPECT_EQ(text.back(), '\n');
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), file.rows() + 1);
  EXPECT_EQ(file.rows(), offered - 1);  // the row that did not fit is not there
}

TEST(OutputBudgetTest, ARunWhoseRowsOutgrowTheEstimateEndsAtTheBudget) {
  const fs::path dir = Dir("outgrown");
  // eight signals whose numbers take 23 characters each, where the estimate
  // reckons 20 with the separator: 20001 rows x 9 columns, estimated
  // 3.43 MiB, written more
  std::string blocks, logs;
  for (int i = 0; i < 8; ++i) {
    const std::string name = "s" + std::to_string(i);
    blocks += "<block type='sine' name='" + name + "' frequency='" + std::to_string(1.3 + i) +
              "' amplitude='-1.2345e-7'/>";
    logs += "<log signal='" + name + ".y'/>";
  }
  std::ofstream(dir / "d.xml") << "<diagram name='d'><blocks>" << blocks
                               << "</blocks><solver t_end='2'/><output interval='1e-4'>" << logs
                               << "</output></diagram>";
  const auto run =
      testing::RunMechflow("run " + (dir / "d.xml").string() + " --max-output 3600K --out " + (dir / "out").string());
  EXPECT_EQ(run.exit_code, 1) << run.out << run.err;
  EXPECT_THAT(run.err, HasSubstr("d.csv' reached the output budget of 3.52 MiB after"));
  const std::string csv = testing::ReadFile(dir / "out" / "d.csv");
  EXPECT_LE(csv.size(), 3600u * 1024);
  EXPECT_GT(csv.size(), 3500u * 1024);
  EXPECT_EQ(csv.back(), '\n');
  EXPECT_THAT(run.out, Not(HasSubstr("(20001 rows)")));
}

// The animation's files have a budget of their own by default (256 MiB): a
// browser holds the whole page. 200 sliding boxes over 1000 s make about
// 100000 frames x 200 bodies x 28 bytes, some 530 MiB, under the 1 GiB of
// the results' budget; --max-output sets both.
TEST(OutputBudgetTest, AnAnimationHasASmallerBudgetByDefault) {
  const fs::path dir = Dir("animation_default");
  std::string xml = "<diagram name='boxes'>\n<mechanism name='m'>\n";
  for (int i = 1; i <= 200; ++i) {
    const std::string b = "b" + std::to_string(i);
    xml += "<body name='" + b + "' mass='1' inertia='1 1 1'/>\n<joint name='j" + std::to_string(i) +
           "' type='translational' body1='Base0' body2='" + b + "' axis='1 0 0'/>\n<shape type='box' body='" + b +
           "' size='0.1 0.1 0.1'/>\n";
  }
  xml += "<sensor name='x' kind='coordinate' dof='j1'/>\n</mechanism>\n<solver t_end='1000'/>\n"
         "<output interval='0.01'><log signal='m.x'/></output>\n"
         "</diagram>\n";
  std::ofstream(dir / "boxes.xml") << xml;
  const auto refused = testing::RunMechflow("run " + (dir / "boxes.xml").string() + " --animate --out " +
                                            (dir / "out").string());
  EXPECT_EQ(refused.exit_code, 2) << refused.out << refused.err;
  EXPECT_THAT(refused.err, HasSubstr("boxes.html would be about"));
  EXPECT_THAT(refused.err, HasSubstr("past the budget of 256 MiB"));
  EXPECT_FALSE(fs::exists(dir / "out" / "boxes.csv"));
}

}  // namespace
}  // namespace mechflow
