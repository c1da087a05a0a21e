// Ctrl-C and SIGTERM (issue 15, item 3): a real signal sent to a running
// `mechflow run` ends it at its next row; the rows so far are written and
// complete, the message says where it stopped, and the exit code is 130 or
// 143 as shells report a process ended by those signals.
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/cli/mechflow_command.h"

extern char** environ;

namespace mechflow {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

struct Ended {
  int exit_code = -1;
  std::string out, err;
};

// Starts a long run (or a sweep of them: `sweep` holds its options), waits
// until it is running, sends `signal`, and collects what it printed.
Ended InterruptedRun(int signal, const fs::path& dir, const std::vector<std::string>& sweep = {}) {
  fs::create_directories(dir);
  // the README's stick-slip example, endless, a row every 0.5 s (so that
  // what it writes when stopped is small)
  std::string xml = testing::ReadFile(std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/stick_slip_blocks.xml");
  xml.replace(xml.find("interval=\"0.001\""), 16, "interval=\"0.5\"");
  const fs::path diagram = dir / "stick_slip_blocks.xml";
  std::ofstream(diagram) << xml;
  const std::string out = (dir / "out").string(), err = (dir / "err").string();
  std::vector<std::string> args = {MECHFLOW_BINARY, sweep.empty() ? "run" : "sweep", diagram.string(), "--t-end",
                                   "1e7", "--out", (dir / "results").string(),
                                   "--max-output", "8G"};  // 2e7 rows would be past the default budget
  args.insert(args.end(), sweep.begin(), sweep.end());
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, MECHFLOW_BINARY, &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  EXPECT_EQ(spawned, 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(800));  // loading takes a few ms; the run some minutes
  kill(pid, signal);
  int status = 0;
  waitpid(pid, &status, 0);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, testing::ReadFile(out), testing::ReadFile(err)};
}

void ExpectCompleteRows(const fs::path& csv) {
  std::stringstream in(testing::ReadFile(csv));
  std::string line;
  ASSERT_TRUE(std::getline(in, line));
  const auto fields = [](const std::string& l) { return std::count(l.begin(), l.end(), ','); };
  const auto width = fields(line);
  int rows = 0;
  double last = -1;
  while (std::getline(in, line)) {
    ASSERT_EQ(fields(line), width) << "row " << rows + 1 << ": " << line;
    last = std::stod(line.substr(0, line.find(',')));
    ++rows;
  }
  EXPECT_GT(rows, 10);
  EXPECT_GT(last, 0.0);
  EXPECT_LT(last, 1e7);
}

TEST(InterruptTest, SigintEndsTheRunWithItsRowsWritten) {
  const fs::path dir = fs::path(::testing::TempDir()) / "interrupt_int";
  const Ended e = InterruptedRun(SIGINT, dir);
  EXPECT_EQ(e.exit_code, 130) << e.err;
  EXPECT_THAT(e.err, HasSubstr("interrupted by SIGINT at t = "));
  EXPECT_THAT(e.err, HasSubstr("the rows up to there are written"));
  EXPECT_THAT(e.out, HasSubstr("wrote "));
  ExpectCompleteRows(dir / "results" / "stick_slip_blocks.csv");
}

TEST(InterruptTest, SigtermAlike) {
  const fs::path dir = fs::path(::testing::TempDir()) / "interrupt_term";
  const Ended e = InterruptedRun(SIGTERM, dir);
  EXPECT_EQ(e.exit_code, 143) << e.err;
  EXPECT_THAT(e.err, HasSubstr("interrupted by SIGTERM at t = "));
  ExpectCompleteRows(dir / "results" / "stick_slip_blocks.csv");
}

// A sweep: the runs under way end with their rows written, the others are
// not started, the summary says which, and the exit code is the signal's.
TEST(InterruptTest, ASweepEndsItsRunsAndStartsNoMore) {
  const fs::path dir = fs::path(::testing::TempDir()) / "interrupt_sweep";
  const Ended e = InterruptedRun(SIGINT, dir, {"--vary", "mu_s=0.5,0.6,0.7", "--jobs", "1"});
  EXPECT_EQ(e.exit_code, 130) << e.err;
  EXPECT_THAT(e.err, HasSubstr("run 1/3 (mu_s=0.5): failed at t = "));
  EXPECT_THAT(e.err, HasSubstr("interrupted by SIGINT"));
  EXPECT_THAT(e.err, HasSubstr("run 2/3 (mu_s=0.6): not run (SIGINT)"));
  EXPECT_THAT(e.err, HasSubstr("run 3/3 (mu_s=0.7): not run (SIGINT)"));
  ExpectCompleteRows(dir / "results" / "stick_slip_blocks.run1.mu_s=0.5.csv");
  const std::string summary = testing::ReadFile(dir / "results" / "stick_slip_blocks.sweep.csv");
  EXPECT_THAT(summary, HasSubstr("\n2,0.6,not run,,interrupted,"));
}

// A run that fails at its start writes what it has (a header) and draws no
// plot of nothing.
TEST(InterruptTest, AFailureAtTheStartDrawsNoPlot) {
  const fs::path dir = fs::path(::testing::TempDir()) / "fail_at_start";
  fs::create_directories(dir);
  std::ofstream(dir / "d.xml") << "<diagram name='d'>\n<blocks><block type='expression' name='f' inputs='' "
                                  "expr=\"error('boom')\"/></blocks>\n<solver t_end='1'/>\n"
                                  "<output interval='0.1' plot='d.png'><log signal='f.y'/></output>\n</diagram>\n";
  const auto run = testing::RunMechflow("run " + (dir / "d.xml").string() + " --out " + (dir / "out").string());
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_THAT(run.err, HasSubstr("simulation failed at t = 0 s"));
  EXPECT_THAT(run.err, HasSubstr("no plot: the run left 0 rows"));
  EXPECT_EQ(testing::ReadFile(dir / "out" / "d.csv"), "time,f.y\n");
  EXPECT_FALSE(fs::exists(dir / "out" / "d.png"));
}

}  // namespace
}  // namespace mechflow
