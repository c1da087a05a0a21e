// `mechflow psd` and the <spectrum> output: the
// Frequencies seed's body 3 peaks at its three natural frequencies; bad input
// exits 2 naming what was expected.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/cli/mechflow_command.h"

namespace mechflow {
namespace {

using ::testing::HasSubstr;
using testing::ReadFile;
using testing::RunMechflow;

namespace fs = std::filesystem;

TEST(PsdCommandTest, FrequenciesRunWritesItsSpectrumAndThePsdCommandAgrees) {
  const fs::path out = fs::path(::testing::TempDir()) / "psd_command";
  const auto run = RunMechflow("run " + std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/frequencies.xml --out " +
                               out.string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_THAT(run.out, HasSubstr("m.z3: peaks"));
  ASSERT_TRUE(fs::exists(out / "frequencies.m.z3.psd.csv"));
  // the command on the same results, with the same segment: the same file
  const auto psd = RunMechflow("psd " + (out / "frequencies.csv").string() +
                               " --signal m.z3 --segment 4096 --peaks 3 --out " + (out / "again").string());
  ASSERT_EQ(psd.exit_code, 0) << psd.err;
  EXPECT_THAT(psd.out, HasSubstr("4096 samples per segment = 2.048 s, 6 segments overlapping by 50 %, Hann window"));
  EXPECT_EQ(ReadFile(out / "again" / "frequencies.psd.csv"), ReadFile(out / "frequencies.m.z3.psd.csv"));
  // its header, and the three peaks within a bin (0.488 Hz) of LA-1's
  std::stringstream csv(ReadFile(out / "again" / "frequencies.psd.csv"));
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header, "frequency [Hz],PSD m.z3 [signal^2/Hz]");
  for (const char* f : {"17.66", "43.81", "67.24"}) EXPECT_THAT(psd.out, HasSubstr(f));
}

TEST(PsdCommandTest, BadInputExits2) {
  const fs::path dir = fs::path(::testing::TempDir()) / "psd_bad";
  fs::create_directories(dir);
  std::ofstream(dir / "r.csv") << "time,x\n0,1\n0.1,2\n0.2,3\n";
  auto outcome = RunMechflow("psd " + (dir / "r.csv").string() + " --signal y --out " + dir.string());
  EXPECT_EQ(outcome.exit_code, 2);
  EXPECT_THAT(outcome.err, HasSubstr("no signal 'y'"));
  outcome = RunMechflow("psd " + (dir / "r.csv").string() + " --signal x --out " + dir.string());
  EXPECT_EQ(outcome.exit_code, 2);
  EXPECT_THAT(outcome.err, HasSubstr("at least 16 are needed"));
  outcome = RunMechflow("psd " + (dir / "r.csv").string() + " --out " + dir.string());
  EXPECT_EQ(outcome.exit_code, 2);
  EXPECT_THAT(outcome.err, HasSubstr("needs --signal"));
  outcome = RunMechflow("psd " + (dir / "r.csv").string() + " --signal x --set c=1 --out " + dir.string());
  EXPECT_EQ(outcome.exit_code, 2);
  EXPECT_THAT(outcome.err, HasSubstr("do not apply"));
  // a <spectrum> of a column that is not logged is refused at its line
  std::ofstream(dir / "d.xml") << "<diagram name='d'>\n<blocks><block type='sine' name='s' amplitude='1' frequency='5'/>"
                                  "</blocks>\n<solver t_end='1'/>\n<output interval='0.001'><log signal='s.y'/>\n"
                                  "<spectrum signal='s.x'/></output>\n</diagram>\n";
  outcome = RunMechflow("run " + (dir / "d.xml").string() + " --out " + dir.string());
  EXPECT_EQ(outcome.exit_code, 2);
  EXPECT_THAT(outcome.err, HasSubstr("d.xml:5: <spectrum>: 's.x' is not a logged column"));
}

// 20 rows of a sine, 0.1 s apart; `edit` changes the text of row `row`
// (1: the first after the header) before it is written.
fs::path Results(const fs::path& dir, int row = 0, const std::string& text = "") {
  fs::create_directories(dir);
  std::ostringstream csv;
  csv << "time,x\n";
  for (int k = 1; k <= 20; ++k) {
    if (k == row) csv << text << "\n";
    else csv << 0.1 * (k - 1) << "," << std::sin(k) << "\n";
  }
  std::ofstream(dir / "r.csv") << csv.str();
  return dir / "r.csv";
}

TEST(PsdCommandTest, RowsOutOfTimeOrderOrNotNumbersAreRefusedAtTheirLine) {
  const fs::path dir = fs::path(::testing::TempDir()) / "psd_rows";
  const std::string options = " --signal x --segment 16 --out " + dir.string();
  auto outcome = RunMechflow("psd " + Results(dir).string() + options);
  ASSERT_EQ(outcome.exit_code, 0) << outcome.err;
  // row 6 (line 7) goes back in time; then repeats the time of row 5
  outcome = RunMechflow("psd " + Results(dir, 6, "0.2,0.5").string() + options);
  EXPECT_EQ(outcome.exit_code, 2);
  EXPECT_THAT(outcome.err, HasSubstr("r.csv:7: time 0.2 is not after the row before (0.4)"));
  outcome = RunMechflow("psd " + Results(dir, 6, "0.4,0.5").string() + options);
  EXPECT_EQ(outcome.exit_code, 2);
  EXPECT_THAT(outcome.err, HasSubstr("r.csv:7: time 0.4 is not after the row before"));
  // a field is a number as a whole: not 1abc (which std::stod read as 1), not hex
  for (const std::string junk : {"0.5,1abc", "0.5,0x10", "0.5,nan", "0.5x,1"}) {
    outcome = RunMechflow("psd " + Results(dir, 6, junk).string() + options);
    EXPECT_EQ(outcome.exit_code, 2) << junk;
    EXPECT_THAT(outcome.err, HasSubstr("r.csv:7: '")) << junk;
    EXPECT_THAT(outcome.err, HasSubstr("' is not a finite number")) << junk;
  }
}

TEST(PsdCommandTest, OptionsOutOfRangeAreUsageErrorsNamingTheOption) {
  const fs::path dir = fs::path(::testing::TempDir()) / "psd_options";
  const std::string base = "psd " + Results(dir).string() + " --signal x --out " + dir.string() + " ";
  const std::pair<std::string, std::string> cases[] = {
      {"--overlap 0.9999999", "--overlap: '0.9999999' is not from 0 to 0.99"},
      {"--overlap -0.1", "--overlap: '-0.1' is not from 0 to 0.99"},
      {"--peaks -1", "--peaks: '-1' is not a whole number from 0 to 1000"},
      {"--peaks 2.5", "--peaks: '2.5' is not a whole number"},
      {"--segment 0x10", "--segment: '0x10' is not a whole number from 16"},
      {"--segment 1e3", "--segment: '1e3' is not a whole number"},
      {"--max-frequency -1", "--max-frequency: '-1' is not a frequency > 0 Hz"},
      {"--max-frequency 1abc", "--max-frequency: '1abc' is not a number"},
      {"--from inf", "--from: 'inf' is not a finite number"},
  };
  for (const auto& [option, message] : cases) {
    const auto outcome = RunMechflow(base + option);
    EXPECT_EQ(outcome.exit_code, 2) << option;
    EXPECT_THAT(outcome.err, HasSubstr("mechflow psd: " + message)) << option;
  }
}

TEST(PsdCommandTest, ASpectrumsOverlapIsBoundedAtItsLine) {
  const fs::path dir = fs::path(::testing::TempDir()) / "psd_overlap";
  fs::create_directories(dir);
  for (const std::string attribute : {"overlap='0.9999999'", "max_frequency='-1'"}) {
    std::ofstream(dir / "d.xml") << "<diagram name='d'>\n<blocks><block type='sine' name='s' amplitude='1' "
                                    "frequency='5'/></blocks>\n<solver t_end='1'/>\n<output interval='0.001'>"
                                    "<log signal='s.y'/>\n<spectrum signal='s.y' " << attribute
                                 << "/></output>\n</diagram>\n";
    const auto outcome = RunMechflow("run " + (dir / "d.xml").string() + " --out " + dir.string());
    EXPECT_EQ(outcome.exit_code, 2) << attribute;
    EXPECT_THAT(outcome.err, HasSubstr("d.xml:5: <spectrum>: ")) << attribute;
    EXPECT_THAT(outcome.err, HasSubstr(attribute.substr(0, attribute.find('=')) + " must be")) << attribute;
    EXPECT_FALSE(fs::exists(dir / "d.csv")) << attribute;  // refused before the run
  }
}

}  // namespace
}  // namespace mechflow
