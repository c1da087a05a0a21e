// `mechflow psd` and the <spectrum> output (issue 14, item 2): the
// Frequencies seed's body 3 peaks at its three natural frequencies; bad input
// exits 2 naming what was expected.
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

}  // namespace
}  // namespace mechflow
