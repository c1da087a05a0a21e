// `mechflow run` driven from scripts: --no-plot (no gnuplot needed),
// --results - (the CSV alone on standard output) and the record that keeps two
// diagram files from overwriting each other's results in one --out.

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/cli/mechflow_command.h"

namespace mechflow::run_for_scripts_test {  // names of its own: the files of its folder are compiled together
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;
using testing::ReadFile;
using testing::RunMechflow;

fs::path FreshDir(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("run_for_scripts_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// x' = -k x, x(0) = 1 (x = exp(-k t)), with a plot and a spectrum of x;
// `extra` goes inside <diagram> (a script).
fs::path WriteDecay(const fs::path& path, const std::string& name, const std::string& extra = "",
                    const std::string& t_end = "2") {
  std::ofstream(path) << "<diagram name='" << name << "'>\n"
                      << "<identifiers><identifier name='k' value='1'/></identifiers>\n"
                         "<blocks><block type='integrator' name='x' initial='1'/>"
                         "<block type='gain' name='g' k='-k'/></blocks>\n"
                         "<connections><connect from='x.y' to='g.u'/><connect from='g.y' to='x.u'/></connections>\n"
                      << extra << "<solver t_end='" << t_end << "' rtol='1e-10' atol='1e-12'/>\n"
                      << "<output interval='0.01' plot='" << name << ".png'><log signal='x.y' label='x'/>"
                         "<spectrum signal='x'/></output>\n</diagram>\n";
  return path;
}

// The rows of a results CSV: its header, then (time, x) per row; fails the
// test on a line that is not two numbers.
struct Table {
  std::string header;
  std::vector<std::pair<double, double>> rows;
};
Table ParseCsv(const std::string& text) {
  Table table;
  std::istringstream in(text);
  std::getline(in, table.header);
  for (std::string line; std::getline(in, line);) {
    const auto comma = line.find(',');
    EXPECT_NE(comma, std::string::npos) << line;
    if (comma == std::string::npos) continue;
    std::size_t used = 0;
    const double t = std::stod(line.substr(0, comma)), x = std::stod(line.substr(comma + 1), &used);
    EXPECT_EQ(comma + 1 + used, line.size()) << "not a number: " << line;
    table.rows.push_back({t, x});
  }
  return table;
}

// Every row of the decay against exp(-t).
void ExpectDecay(const Table& table, std::size_t rows) {
  EXPECT_EQ(table.header, "time,x");
  ASSERT_EQ(table.rows.size(), rows);
  double worst = 0;
  for (const auto& [t, x] : table.rows) worst = std::max(worst, std::abs(x - std::exp(-t)));
  EXPECT_LT(worst, 1e-8);
}

std::vector<std::string> FilesIn(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(RunForScriptsTest, NoPlotWritesTheCsvAndNoPlotAndNeedsNoGnuplot) {
  const fs::path dir = FreshDir("no_plot");
  const fs::path diagram = WriteDecay(dir / "decay.xml", "decay");
  // a PATH without gnuplot (nor anything else): mechflow starts no program
  fs::create_directories(dir / "empty_bin");
  const auto run = RunMechflow("run " + diagram.string() + " --no-plot --out " + (dir / "out").string(),
                               "PATH=" + (dir / "empty_bin").string() + " ");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_THAT(run.err, Not(HasSubstr("gnuplot")));
  EXPECT_THAT(run.err, Not(HasSubstr("plot")));
  EXPECT_EQ(FilesIn(dir / "out"), (std::vector<std::string>{".mechflow-outputs", "decay.csv", "decay.units.csv",
                                                            "decay.x.psd.csv"}));
  ExpectDecay(ParseCsv(ReadFile(dir / "out" / "decay.csv")), 201);

  // the same run with its plot: the CSV files are the same bytes
  const auto plotted = RunMechflow("run " + diagram.string() + " --out " + (dir / "plotted").string());
  ASSERT_EQ(plotted.exit_code, 0) << plotted.err;
  for (const char* file : {"decay.csv", "decay.units.csv", "decay.x.psd.csv"})
    EXPECT_EQ(ReadFile(dir / "out" / file), ReadFile(dir / "plotted" / file)) << file;
  EXPECT_TRUE(fs::exists(dir / "plotted" / "decay.png.gp"));

  // a sweep draws no overlay either
  const auto sweep = RunMechflow("sweep " + diagram.string() + " --vary k=1,2 --no-plot --out " +
                                     (dir / "sweep").string(),
                                 "PATH=" + (dir / "empty_bin").string() + " ");
  ASSERT_EQ(sweep.exit_code, 0) << sweep.err;
  EXPECT_THAT(sweep.err, Not(HasSubstr("plot")));
  EXPECT_EQ(FilesIn(dir / "sweep"), (std::vector<std::string>{".mechflow-outputs", "decay.run1.k=1.csv",
                                                              "decay.run2.k=2.csv", "decay.sweep.csv"}));
  ExpectDecay(ParseCsv(ReadFile(dir / "sweep" / "decay.run1.k=1.csv")), 201);
}

TEST(RunForScriptsTest, ResultsOnStandardOutputAreTheCsvAlone) {
  const fs::path dir = FreshDir("stdout");
  // a control script that prints: its line goes to standard error, not into the CSV
  const fs::path diagram =
      WriteDecay(dir / "decay.xml", "decay",
                 "<script>\nlocal said = false\nfunction step(sim)\n"
                 "  if not said then print('hello from the script'); said = true end\nend\n</script>\n");
  const auto file_run = RunMechflow("run " + diagram.string() + " --out " + (dir / "file").string());
  ASSERT_EQ(file_run.exit_code, 0) << file_run.err;

  // no --out: run in a folder of its own, which stays as it was
  fs::create_directories(dir / "cwd");
  const auto piped = RunMechflow("run " + diagram.string() + " --results -", "cd " + (dir / "cwd").string() + " && ");
  ASSERT_EQ(piped.exit_code, 0) << piped.err;
  EXPECT_EQ(piped.out, ReadFile(dir / "file" / "decay.csv"));
  ExpectDecay(ParseCsv(piped.out), 201);
  EXPECT_TRUE(FilesIn(dir / "cwd").empty());
  EXPECT_THAT(piped.err, HasSubstr("hello from the script"));
  EXPECT_THAT(piped.err, HasSubstr("mechflow run " + diagram.string() + ": t = 0 .. 2 s"));
  EXPECT_THAT(piped.err, HasSubstr("wrote the results to standard output (201 rows)"));
  EXPECT_THAT(piped.err, HasSubstr("note: --results - without --out writes the results only, not decay.units.csv, "
                                   "decay.changes.csv (if the script changes identifiers), decay.x.psd.csv (give "
                                   "--out DIR for them)"));
  EXPECT_THAT(piped.err, HasSubstr("note: --results - draws no plot (gnuplot draws from files): not decay.png, "
                                   "decay.x.psd.png"));

  // with --out, the other files go there; --no-plot leaves its note out; --quiet every message
  const auto with_out = RunMechflow("run " + diagram.string() + " --results - --no-plot --quiet --out " +
                                    (dir / "other").string());
  ASSERT_EQ(with_out.exit_code, 0) << with_out.err;
  EXPECT_EQ(with_out.out, piped.out);
  EXPECT_EQ(with_out.err, "hello from the script\n");  // the script's own print is not a message of mechflow
  EXPECT_EQ(FilesIn(dir / "other"),
            (std::vector<std::string>{".mechflow-outputs", "decay.units.csv", "decay.x.psd.csv"}));
  EXPECT_EQ(ReadFile(dir / "other" / "decay.units.csv"), ReadFile(dir / "file" / "decay.units.csv"));
}

TEST(RunForScriptsTest, AFailedRunLeavesItsRowsOnStandardOutput) {
  const fs::path dir = FreshDir("stdout_failed");
  const fs::path diagram = WriteDecay(
      dir / "decay.xml", "decay", "<script>\nfunction step(sim)\n  if sim.t > 0.455 then error('no') end\nend\n</script>\n");
  const auto run = RunMechflow("run " + diagram.string() + " --results -");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_THAT(run.err, HasSubstr("step(sim) at t = 0.46 s failed: "));
  const Table table = ParseCsv(run.out);
  ExpectDecay(table, 46);  // t = 0 .. 0.45
  EXPECT_DOUBLE_EQ(table.rows.back().first, 0.45);
}

TEST(RunForScriptsTest, WhatResultsOnStandardOutputCannotDoIsRefused) {
  const fs::path dir = FreshDir("stdout_refused");
  const fs::path diagram = WriteDecay(dir / "decay.xml", "decay");
  auto outcome = RunMechflow("sweep " + diagram.string() + " --vary k=1,2 --results - --out " + dir.string());
  EXPECT_EQ(outcome.exit_code, 2);
  EXPECT_THAT(outcome.err, HasSubstr("--results - (standard output) is for mechflow run: a sweep writes a results "
                                     "file per run; give --results NAME.csv"));
  outcome = RunMechflow("run " + diagram.string() + " --results - --animate");
  EXPECT_EQ(outcome.exit_code, 2);
  EXPECT_THAT(outcome.err, HasSubstr("--animate writes a file into the output folder, and --results - without --out "
                                     "has none: give --out DIR"));
  EXPECT_EQ(outcome.out, "");
}

TEST(RunForScriptsTest, TwoDiagramFilesOfOneNameDoNotOverwriteEachOther) {
  const fs::path dir = FreshDir("claims");
  fs::create_directories(dir / "a");
  fs::create_directories(dir / "b");
  const fs::path a = WriteDecay(dir / "a" / "decay.xml", "decay", "", "1");
  const fs::path b = WriteDecay(dir / "b" / "decay.xml", "decay", "", "2");  // a copy, changed
  const std::string out = " --no-plot --out " + (dir / "out").string();
  ASSERT_EQ(RunMechflow("run " + a.string() + out).exit_code, 0);
  const std::string first = ReadFile(dir / "out" / "decay.csv");
  ExpectDecay(ParseCsv(first), 101);

  // the same diagram file again, by another spelling of its path: the everyday case
  const auto again = RunMechflow("run " + (dir / "a" / ".." / "a" / "decay.xml").string() + out);
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_EQ(again.err, "");

  // the copy is refused before it runs, naming both files and what to do
  const auto refused = RunMechflow("run " + b.string() + out);
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_EQ(refused.out, "");
  EXPECT_THAT(refused.err, HasSubstr(b.string() + ": not run: the output folder '" + (dir / "out").string() +
                                     "' holds the files decay.* written by '" + a.string() +
                                     "' (named so here by the diagram's name \"decay\")"));
  EXPECT_THAT(refused.err, HasSubstr("Give another --out, name this diagram's outputs otherwise"));
  EXPECT_THAT(refused.err, HasSubstr("or pass --overwrite"));
  EXPECT_EQ(ReadFile(dir / "out" / "decay.csv"), first);
  // so are its sweep and its modes, which name their files after it too
  EXPECT_EQ(RunMechflow("sweep " + b.string() + " --vary k=1,2" + out).exit_code, 2);
  EXPECT_EQ(RunMechflow("modes " + b.string() + " --out " + (dir / "out").string()).exit_code, 2);
  EXPECT_FALSE(fs::exists(dir / "out" / "decay.sweep.csv"));
  EXPECT_FALSE(fs::exists(dir / "out" / "decay.modes.csv"));

  // another name, or --results NAME, in the same folder: both kept
  const auto renamed = RunMechflow("run " + b.string() + " --results decay_b.csv" + out);
  ASSERT_EQ(renamed.exit_code, 0) << renamed.err;
  ExpectDecay(ParseCsv(ReadFile(dir / "out" / "decay_b.csv")), 201);
  EXPECT_EQ(ReadFile(dir / "out" / "decay.csv"), first);

  // --overwrite hands the name over, and says so
  const auto taken = RunMechflow("run " + b.string() + " --overwrite" + out);
  ASSERT_EQ(taken.exit_code, 0) << taken.err;
  EXPECT_THAT(taken.out, HasSubstr("--overwrite: " + b.string() + " replaces decay.* (written before by '" +
                                   a.string() + "')"));
  ExpectDecay(ParseCsv(ReadFile(dir / "out" / "decay.csv")), 201);
  EXPECT_EQ(RunMechflow("run " + a.string() + out).exit_code, 2);  // now the first is the other one
  EXPECT_EQ(RunMechflow("run " + b.string() + out).exit_code, 0);
}

// Commands started together into one folder: the record is locked while one
// checks and adds its names, so the next reads them. Here the test holds the
// lock, as a command in the middle of its check would, and adds a name.
TEST(RunForScriptsTest, TheRecordIsLockedWhileANameIsAdded) {
  const fs::path dir = FreshDir("claims_locked");
  const fs::path diagram = WriteDecay(dir / "decay.xml", "decay");
  fs::create_directories(dir / "out");
  const fs::path record = dir / "out" / ".mechflow-outputs";
  // O_CLOEXEC: the command started below must not inherit the descriptor, and the lock with it
  const int fd = ::open(record.c_str(), O_RDWR | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::flock(fd, LOCK_EX), 0);
  const std::string command = "(" + std::string(MECHFLOW_BINARY) + " run " + diagram.string() +
                              " --no-plot --quiet --out " + (dir / "out").string() + " 2>" + (dir / "err").string() +
                              "; echo $? >" + (dir / "code.part").string() + "; mv " + (dir / "code.part").string() +
                              " " + (dir / "code").string() + ") &";
  ASSERT_EQ(std::system(command.c_str()), 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(500));  // the whole run takes a tenth of that
  EXPECT_FALSE(fs::exists(dir / "code"));  // waiting for the lock
  const std::string line = "decay\t/elsewhere/decay.xml\n";
  ASSERT_EQ(::write(fd, line.data(), line.size()), static_cast<ssize_t>(line.size()));
  ::close(fd);  // the lock goes with it
  for (int i = 0; i < 600 && !fs::exists(dir / "code"); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_EQ(ReadFile(dir / "code"), "2\n");
  EXPECT_THAT(ReadFile(dir / "err"), HasSubstr("holds the files decay.* written by '/elsewhere/decay.xml'"));
  EXPECT_FALSE(fs::exists(dir / "out" / "decay.csv"));
}

TEST(RunForScriptsTest, AnUnreadableRecordIsRefusedAtItsLine) {
  const fs::path dir = FreshDir("claims_bad");
  const fs::path diagram = WriteDecay(dir / "decay.xml", "decay");
  fs::create_directories(dir / "out");
  std::ofstream(dir / "out" / ".mechflow-outputs") << "# a comment\ndecay without a tab\n";
  const auto run = RunMechflow("run " + diagram.string() + " --no-plot --out " + (dir / "out").string());
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr((dir / "out" / ".mechflow-outputs").string() + ":2: not STEM<tab>DIAGRAM FILE"));
  EXPECT_FALSE(fs::exists(dir / "out" / "decay.csv"));
}

}  // namespace
}  // namespace mechflow::run_for_scripts_test
