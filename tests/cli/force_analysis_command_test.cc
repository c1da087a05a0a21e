// `mechflow force-analysis` as a user runs it: the seed's
// Fig. 7.10 run -- ElastFriction2's friction element, K and delta against
// mu = mu0 at three amplitudes -- and its files; bad input exits 2.
#include <filesystem>
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

const std::string kExample = std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/elast_friction2.xml";

std::vector<std::vector<std::string>> ReadCsv(const std::filesystem::path& path) {
  std::vector<std::vector<std::string>> rows;
  std::stringstream in(ReadFile(path));
  for (std::string line; std::getline(in, line);) {
    rows.emplace_back();
    std::stringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) rows.back().push_back(cell);
  }
  return rows;
}

TEST(ForceAnalysisCommandTest, ElasticFriction2StiffnessAgainstFriction) {
  const auto out = std::filesystem::path(::testing::TempDir()) / "force_analysis_command";
  const auto outcome = RunMechflow("force-analysis " + kExample +
                                   " --element friction --amplitude 0.001,0.003 --frequency 1"
                                   " --vary ffr,ffr0=0,0.2,0.5 --samples 2000 --out " + out.string());
  ASSERT_EQ(outcome.exit_code, 0) << outcome.err;
  EXPECT_THAT(outcome.out, HasSubstr("element 'friction'"));
  const auto table = ReadCsv(out / "elast_friction2.force_analysis.csv");
  ASSERT_EQ(table.size(), 7u);  // a header and 3 x 2 cases
  EXPECT_EQ(table[0][0], "ffr=ffr0");
  EXPECT_EQ(table[0][4], "K");
  const double K[] = {80.00, 86.83, 117.58};
  for (int i = 0; i < 6; ++i) {
    EXPECT_NEAR(std::stod(table[1 + i][4]), K[i / 2], 6e-3 * K[i / 2]) << "row " << i;
    EXPECT_EQ(table[1 + i][8], "yes");
  }
  // the loops: x', v, R per case over the last period, 2001 rows
  const auto loops = ReadCsv(out / "elast_friction2.force_analysis.loops.csv");
  ASSERT_EQ(loops.size(), 2002u);
  EXPECT_EQ(loops[0].size(), 18u);
  EXPECT_EQ(loops[0][0], "x' ffr=0 a=0.001 f=1");
  // K and delta against mu, one curve per amplitude
  const auto curves = ReadCsv(out / "elast_friction2.force_analysis.curves.csv");
  ASSERT_EQ(curves.size(), 4u);
  EXPECT_EQ(curves[0][0], "ffr");
  EXPECT_NEAR(std::stod(curves[3][1]), 117.58, 0.7);
  EXPECT_NEAR(std::stod(curves[3][2]), 9.23, 0.02);
  // K and delta are drawn from zero: a constant shows flat, not its round-off
  EXPECT_THAT(ReadFile(out / "elast_friction2.force_analysis.png.gp"), HasSubstr("set yrange [*<0:0<*]"));
  if (outcome.err.find("no plot") == std::string::npos) {  // gnuplot installed
    EXPECT_TRUE(std::filesystem::file_size(out / "elast_friction2.force_analysis.loops.png") > 1000);
    EXPECT_TRUE(std::filesystem::file_size(out / "elast_friction2.force_analysis.png") > 1000);
  }
}

TEST(ForceAnalysisCommandTest, BadInputExits2) {
  const std::string base = "force-analysis " + kExample + " --out " + ::testing::TempDir() + "/fa_bad";
  EXPECT_THAT(RunMechflow(base + " --amplitude 0.001 --frequency 1").err, HasSubstr("needs --element"));
  auto outcome = RunMechflow(base + " --element frction --amplitude 0.001 --frequency 1");
  EXPECT_EQ(outcome.exit_code, 2);
  EXPECT_THAT(outcome.err, HasSubstr("did you mean 'friction'"));
  outcome = RunMechflow(base + " --element constant --amplitude 0.001 --frequency 1");
  EXPECT_EQ(outcome.exit_code, 2);
  EXPECT_THAT(outcome.err, HasSubstr("has no scalar coordinate"));
  outcome = RunMechflow(base + " --element friction --amplitude 0.001 --frequency 0");
  EXPECT_EQ(outcome.exit_code, 2);
  EXPECT_THAT(outcome.err, HasSubstr("frequency must be > 0"));
  outcome = RunMechflow(base + " --element friction --amplitude 0.001 --frequencies 0:1:3");
  EXPECT_EQ(outcome.exit_code, 2);
  EXPECT_THAT(outcome.err, HasSubstr("a log range needs A, B > 0"));
  outcome = RunMechflow(base + " --element friction --amplitude 0.001 --frequency 1 --t-end 3");
  EXPECT_EQ(outcome.exit_code, 2);
  EXPECT_THAT(outcome.err, HasSubstr("--t-end does not apply"));
  outcome = RunMechflow(base + " --element friction --amplitude 0.001 --frequency 1 --vary mu=1,2");
  EXPECT_EQ(outcome.exit_code, 2);
}

// No wrong figure with exit 0: a case whose numbers overflow fails (exit 1,
// the reason on stderr), and nothing printed or written is inf or nan.
TEST(ForceAnalysisCommandTest, AnAmplitudeWhoseNumbersOverflowFailsTheCase) {
  const auto out = std::filesystem::path(::testing::TempDir()) / "fa_overflow";
  const auto outcome = RunMechflow("force-analysis " + kExample + " --element friction --amplitude 0.001,1e300" +
                                   " --frequency 1 --samples 200 --cycles 3 --out " + out.string());
  EXPECT_EQ(outcome.exit_code, 1) << outcome.err;
  EXPECT_THAT(outcome.err, HasSubstr("failed: "));
  EXPECT_THAT(outcome.err, HasSubstr("not a finite number"));
  const std::string csv = ReadFile(out / "elast_friction2.force_analysis.csv");
  for (const std::string& text : {outcome.out, csv, ReadFile(out / "elast_friction2.force_analysis.loops.csv")})
    for (const char* word : {"nan", "inf"}) EXPECT_EQ(text.find(word), std::string::npos) << word << " in " << text;
  const auto table = ReadCsv(out / "elast_friction2.force_analysis.csv");
  ASSERT_EQ(table.size(), 3u);
  EXPECT_EQ(table[1][7], "yes");
  EXPECT_EQ(table[2][7], "no");  // never periodic with no figures
}

TEST(ForceAnalysisCommandTest, NumericOptionsAreStrictAndInRange) {
  const std::string base = "force-analysis " + kExample + " --element friction --out " + ::testing::TempDir() +
                           "/fa_options ";
  const std::pair<std::string, std::string> cases[] = {
      {"--amplitude 1abc --frequency 1", "--amplitude: '1abc' is not a number"},
      {"--amplitude 0x10 --frequency 1", "--amplitude: '0x10' is not a number"},
      {"--amplitude -0.001 --frequency 1", "--amplitude: '-0.001' holds -0.001; an amplitude must be > 0"},
      {"--amplitude 0.001 --frequency 1,-2", "--frequency: '1,-2' holds -2; a frequency must be > 0"},
      {"--amplitude 0.001 --frequency inf", "--frequency: 'inf' is not a finite number"},
      {"--amplitude 0.001 --frequency 1 --cycles 1e1", "--cycles: '1e1' is not a whole number from 2"},
      {"--amplitude 0.001 --frequency 1 --cycles 1", "--cycles: '1' is not a whole number from 2"},
      {"--amplitude 0.001 --frequency 1 --samples 8", "--samples: '8' is not a whole number from 16"},
      {"--amplitude 0.001 --frequency 1 --vary ffr=0.1,0.2x", "--vary ffr: '0.2x' is not a number"},
      {"--amplitude 0.001 --frequency 1 --cycles 100000 --samples 1000", "rows per case is more than 10000000"},
  };
  for (const auto& [options, message] : cases) {
    const auto outcome = RunMechflow(base + options);
    EXPECT_EQ(outcome.exit_code, 2) << options;
    EXPECT_THAT(outcome.err, HasSubstr(message)) << options;
  }
}

// Ctrl-C ends the case under way; the cases finished are written and the
// exit code is 130, as for a run.
TEST(ForceAnalysisCommandTest, SigintWritesTheCasesFinished) {
  const auto out = std::filesystem::path(::testing::TempDir()) / "fa_interrupt";
  std::filesystem::remove_all(out);
  // about a second per case; the signal comes after 0.8 s
  const auto outcome = RunMechflow("force-analysis " + kExample + " --element friction --amplitude 0.001" +
                                   " --frequency 1,2,3,4,5,6,7,8 --cycles 400 --out " + out.string(),
                                   "timeout --preserve-status -s INT 0.8 ");
  EXPECT_EQ(outcome.exit_code, 130) << outcome.err;
  EXPECT_THAT(outcome.err, HasSubstr("SIGINT after "));
  EXPECT_THAT(outcome.err, HasSubstr(" of 8 cases; writing those, no plots"));
  const auto table = ReadCsv(out / "elast_friction2.force_analysis.csv");
  ASSERT_GE(table.size(), 1u);
  EXPECT_LT(table.size(), 9u);
  for (std::size_t i = 1; i < table.size(); ++i) EXPECT_EQ(table[i][7], "yes");
  EXPECT_FALSE(std::filesystem::exists(out / "elast_friction2.force_analysis.loops.png"));
}

}  // namespace
}  // namespace mechflow
