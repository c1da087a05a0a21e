// Ctrl-C, SIGTERM and SIGHUP: a real signal sent to a running `mechflow run`
// ends it at its next row; the rows so far are written and complete, the
// message says where it stopped, and the exit code is 130, 143 or 129 as
// shells report a process ended by those signals. A signal while gnuplot
// draws stops gnuplot and ends the command alike.
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
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

// How to start mechflow: its arguments after the program, and its
// surroundings.
struct Start {
  std::vector<std::string> args;
  std::string path_first;      // a folder put first on PATH (a fake gnuplot)
  bool own_group = false;      // in a process group of its own, as a terminal's job is
  bool ignoring_hup = false;   // started with SIGHUP ignored, as nohup does
};

// Starts mechflow with its output into dir/out and dir/err; returns its pid.
pid_t Spawn(const Start& start, const fs::path& dir) {
  std::vector<std::string> args = {MECHFLOW_BINARY};
  args.insert(args.end(), start.args.begin(), start.args.end());
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::vector<std::string> environment;
  for (char** e = environ; *e; ++e)
    if (std::string(*e).rfind("PATH=", 0) != 0) environment.push_back(*e);
  const char* path = std::getenv("PATH");
  environment.push_back("PATH=" + (start.path_first.empty() ? "" : start.path_first + ":") + (path ? path : ""));
  std::vector<char*> envp;
  for (auto& e : environment) envp.push_back(e.data());
  envp.push_back(nullptr);
  const std::string out = (dir / "out").string(), err = (dir / "err").string();
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  if (start.own_group) {
    posix_spawnattr_setpgroup(&attributes, 0);
    posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);
  }
  // an ignored signal stays ignored in the child
  const auto old_hup = start.ignoring_hup ? std::signal(SIGHUP, SIG_IGN) : nullptr;
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, MECHFLOW_BINARY, &actions, &attributes, argv.data(), envp.data());
  if (start.ignoring_hup) std::signal(SIGHUP, old_hup);
  posix_spawnattr_destroy(&attributes);
  posix_spawn_file_actions_destroy(&actions);
  EXPECT_EQ(spawned, 0);
  return pid;
}

Ended Collect(pid_t pid, const fs::path& dir) {
  int status = 0;
  waitpid(pid, &status, 0);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, testing::ReadFile(dir / "out"), testing::ReadFile(dir / "err")};
}

// The README's stick-slip example in `dir`, endless, a row every 0.5 s (so
// that what it writes when stopped is small); returns its path.
std::string EndlessDiagram(const fs::path& dir) {
  fs::create_directories(dir);
  std::string xml = testing::ReadFile(std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/stick_slip_blocks.xml");
  xml.replace(xml.find("interval=\"0.001\""), 16, "interval=\"0.5\"");
  const fs::path diagram = dir / "stick_slip_blocks.xml";
  std::ofstream(diagram) << xml;
  return diagram.string();
}

// Starts a long run (or a sweep of them: `sweep` holds its options), waits
// until it is running, sends `signal`, and collects what it printed.
Ended InterruptedRun(int signal, const fs::path& dir, const std::vector<std::string>& sweep = {}) {
  Start start;
  // 2e7 rows would be past the default output budget
  start.args = {sweep.empty() ? "run" : "sweep", EndlessDiagram(dir), "--t-end", "1e7", "--out",
                (dir / "results").string(), "--max-output", "8G"};
  start.args.insert(start.args.end(), sweep.begin(), sweep.end());
  const pid_t pid = Spawn(start, dir);
  std::this_thread::sleep_for(std::chrono::milliseconds(800));  // loading takes a few ms; the run some minutes
  kill(pid, signal);
  return Collect(pid, dir);
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

// A closed terminal (SIGHUP) ends a run as SIGTERM does.
TEST(InterruptTest, SighupAlike) {
  const fs::path dir = fs::path(::testing::TempDir()) / "interrupt_hup";
  const Ended e = InterruptedRun(SIGHUP, dir);
  EXPECT_EQ(e.exit_code, 129) << e.err;
  EXPECT_THAT(e.err, HasSubstr("interrupted by SIGHUP at t = "));
  ExpectCompleteRows(dir / "results" / "stick_slip_blocks.csv");
}

// Under nohup (SIGHUP ignored when it starts) a closed terminal does not end it.
TEST(InterruptTest, AnIgnoredSighupStaysIgnored) {
  const fs::path dir = fs::path(::testing::TempDir()) / "interrupt_nohup";
  Start start;
  start.args = {"run", EndlessDiagram(dir), "--t-end", "1e7", "--out", (dir / "results").string(), "--max-output",
                "8G"};
  start.ignoring_hup = true;
  const pid_t pid = Spawn(start, dir);
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  kill(pid, SIGHUP);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  int status = 0;
  EXPECT_EQ(waitpid(pid, &status, WNOHANG), 0) << "ended by an ignored SIGHUP";
  kill(pid, SIGTERM);
  const Ended e = Collect(pid, dir);
  EXPECT_EQ(e.exit_code, 143) << e.err;
}

// A signal while gnuplot draws (a fake gnuplot first on PATH that sleeps)
// stops gnuplot within a second or two: the plot is said not to be drawn
// because of it, the files before it stay, and the command exits with the
// signal's code. `terminal`: the signal goes to the whole process group, as a
// terminal's Ctrl-C does, and reaches gnuplot too.
struct DuringPlot {
  std::string name;
  int signal;
  bool terminal;
  bool psd;  // `mechflow psd` (no run before the plot) instead of `mechflow run`
};

class SignalDuringPlotTest : public ::testing::TestWithParam<DuringPlot> {};

TEST_P(SignalDuringPlotTest, StopsGnuplotAndExitsWithTheSignalsCode) {
  const DuringPlot& c = GetParam();
  const fs::path dir = fs::path(::testing::TempDir()) / ("interrupt_plot_" + c.name);
  fs::remove_all(dir);
  fs::create_directories(dir / "bin");
  const fs::path pid_file = dir / "gnuplot.pid";
  std::ofstream(dir / "bin" / "gnuplot") << "#!/bin/sh\necho $$ >" << pid_file.string() << ".part && mv "
                                         << pid_file.string() << ".part " << pid_file.string() << "\nexec sleep 20\n";
  fs::permissions(dir / "bin" / "gnuplot", fs::perms::owner_all);
  std::ofstream(dir / "d.xml") << "<diagram name='d'>\n<blocks><block type='sine' name='s'/></blocks>\n"
                                  "<solver t_end='1'/>\n<output interval='0.01' plot='d.png'><log signal='s.y'/>"
                                  "</output>\n</diagram>\n";
  std::ofstream csv(dir / "r.csv");
  csv << "time,x\n";
  for (int i = 0; i < 64; ++i) csv << i * 0.01 << "," << (i % 4) << "\n";
  csv.close();
  Start start;
  start.args = c.psd ? std::vector<std::string>{"psd", (dir / "r.csv").string(), "--signal", "x"}
                     : std::vector<std::string>{"run", (dir / "d.xml").string()};
  start.args.insert(start.args.end(), {"--out", (dir / "results").string()});
  start.path_first = (dir / "bin").string();
  start.own_group = c.terminal;
  const pid_t pid = Spawn(start, dir);
  const auto began = std::chrono::steady_clock::now();
  while (!fs::exists(pid_file) && std::chrono::steady_clock::now() - began < std::chrono::seconds(10))
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ASSERT_TRUE(fs::exists(pid_file)) << "gnuplot never started";
  const pid_t gnuplot = std::stoi(testing::ReadFile(pid_file));
  const auto signalled = std::chrono::steady_clock::now();
  kill(c.terminal ? -pid : pid, c.signal);
  const Ended e = Collect(pid, dir);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - signalled).count();
  const bool gnuplot_gone = kill(gnuplot, 0) != 0;
  if (!gnuplot_gone) kill(gnuplot, SIGKILL);
  EXPECT_EQ(e.exit_code, 128 + c.signal) << e.err;
  EXPECT_LT(seconds, 5.0);
  EXPECT_TRUE(gnuplot_gone);
  const std::string plot = (dir / "results" / (c.psd ? "r.psd.png" : "d.png")).string();
  EXPECT_THAT(e.err, HasSubstr("no plot '" + plot + "': SIG" + sigabbrev_np(c.signal)));
  EXPECT_THAT(e.err, HasSubstr(" came while gnuplot drew it, which was stopped"));
  EXPECT_FALSE(fs::exists(plot));
  const std::string data = (dir / "results" / (c.psd ? "r.psd.csv" : "d.csv")).string();
  EXPECT_THAT(e.out, HasSubstr("wrote " + data));
  EXPECT_TRUE(fs::exists(data));
}

INSTANTIATE_TEST_SUITE_P(Signals, SignalDuringPlotTest,
                         ::testing::Values(DuringPlot{"term", SIGTERM, false, false},
                                           DuringPlot{"terminal_int", SIGINT, true, false},
                                           DuringPlot{"psd_hup", SIGHUP, false, true}),
                         [](const auto& info) { return info.param.name; });

}  // namespace
}  // namespace mechflow
