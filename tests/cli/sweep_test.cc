// `mechflow sweep`, run as a user would: the damping ratio of DampingRatio
// (diagrams/examples/damping_ratio.xml, docs/ELEMENTS.md 9.1) swept and
// each run's decay checked against the closed form of the damped oscillator
//   z(t) = 0.5 e^(-beta w t) (cos wd t + beta/sqrt(1-beta^2) sin wd t),
//   w = 2 pi f (f = 1 Hz), wd = w sqrt(1 - beta^2)
// (equilibrium at z = 0, released from rest 0.5 m above it); failed rows, bad
// --vary input, threads against one thread, MPI ranks against threads.

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli/sweep.h"
#include "cli/vary_pattern.h"
#include "tests/cli/mechflow_command.h"

namespace mechflow::cli::sweep_test {  // names of its own: the files of its folder are compiled together
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;
namespace fs = std::filesystem;

using Outcome = mechflow::testing::CommandOutcome;
using mechflow::testing::ReadFile;

Outcome Mechflow(const std::string& args) { return mechflow::testing::RunMechflow(args); }

const std::string kDampingRatio = std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/damping_ratio.xml";

fs::path FreshDir(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("sweep_" + std::to_string(getpid()) + "_" + name);
  fs::remove_all(dir);
  return dir;
}

// damping_ratio.xml with max_steps given by an identifier `steps` (so a
// sweep can starve a run honestly) and a <report> of the lowest z.
fs::path DampingRatioWithReport() {
  std::string xml = ReadFile(kDampingRatio);
  auto replace = [&](const std::string& what, const std::string& with) {
    const auto at = xml.find(what);
    if (at == std::string::npos) throw std::runtime_error("damping_ratio.xml has no '" + what + "'");
    xml.replace(at, what.size(), with);
  };
  replace("<identifier name=\"beta\"", "<identifier name=\"steps\" value=\"500000\"/>\n    <identifier name=\"beta\"");
  replace("<solver t_end=\"10\"", "<solver t_end=\"10\" max_steps=\"steps\"");
  replace("</output>", "  <report min=\"m.z\" label=\"lowest z\" unit=\"m\"/>\n  </output>");
  const fs::path path = fs::path(::testing::TempDir()) / ("damping_report_" + std::to_string(getpid()) + ".xml");
  std::ofstream(path) << xml;
  return path;
}

// One CSV line split into fields ("..." fields unquoted).
std::vector<std::string> SplitCsv(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') fields.back() += '"', ++i;
      else if (c == '"') quoted = false;
      else fields.back() += c;
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  return fields;
}

std::vector<std::vector<std::string>> ReadCsv(const fs::path& p) {
  std::ifstream in(p);
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(in, line);) rows.push_back(SplitCsv(line));
  return rows;
}

// Local maxima of z on the output grid, each refined by the parabola through
// it and its neighbours: (time, value).
std::vector<std::pair<double, double>> Peaks(const fs::path& results) {
  const auto rows = ReadCsv(results);
  std::vector<double> t, z;
  for (std::size_t r = 1; r < rows.size(); ++r) t.push_back(std::stod(rows[r][0])), z.push_back(std::stod(rows[r][1]));
  std::vector<std::pair<double, double>> peaks;
  for (std::size_t i = 1; i + 1 < z.size(); ++i) {
    if (!(z[i] > z[i - 1] && z[i] >= z[i + 1])) continue;
    const double h = t[i + 1] - t[i];
    const double a = (z[i + 1] - 2 * z[i] + z[i - 1]) / 2, b = (z[i + 1] - z[i - 1]) / 2;
    peaks.push_back({t[i] - h * b / (2 * a), z[i] - b * b / (4 * a)});
  }
  return peaks;
}

TEST(SweepTest, HelpNamesTheCommand) {
  EXPECT_THAT(Mechflow("--help").out, HasSubstr("sweep"));
  const Outcome help = Mechflow("help sweep");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_THAT(help.out, StartsWith("usage: mechflow sweep FILE --vary NAME=V1,V2,..."));
  EXPECT_EQ(Mechflow("sweep --help").out, help.out);
}

// Every row's decay rate and damped period, measured on its own results,
// against sigma = beta w and Td = 1/(f sqrt(1 - beta^2)).
TEST(SweepTest, DampingRatioDecayPerRow) {
  const fs::path dir = FreshDir("decay");
  const Outcome o = Mechflow("sweep " + kDampingRatio + " --vary beta=0.05,0.1,0.2 --jobs 2 --out " + dir.string());
  ASSERT_EQ(o.exit_code, 0) << o.err;
  EXPECT_THAT(o.out, HasSubstr("3 runs, 2 at a time"));
  EXPECT_THAT(o.out, HasSubstr("run 2/3 (beta=0.1): ok, t = 10 s"));

  const auto summary = ReadCsv(dir / "damping_ratio.sweep.csv");
  ASSERT_EQ(summary.size(), 4u);
  EXPECT_EQ(summary[0], (std::vector<std::string>{"run", "beta", "status", "t_reached", "error", "results"}));
  const double betas[] = {0.05, 0.1, 0.2};
  const double w = 2 * std::numbers::pi;
  for (int r = 0; r < 3; ++r) {
    const auto& row = summary[r + 1];
    SCOPED_TRACE("row " + std::to_string(r + 1));
    ASSERT_EQ(row.size(), 6u);
    EXPECT_EQ(row[0], std::to_string(r + 1));
    EXPECT_EQ(std::stod(row[1]), betas[r]);
    EXPECT_EQ(row[2], "ok");
    EXPECT_EQ(std::stod(row[3]), 10.0);
    EXPECT_EQ(row[4], "");
    ASSERT_TRUE(fs::exists(dir / row[5])) << row[5];
    EXPECT_THAT(row[5], HasSubstr(".run" + std::to_string(r + 1) + ".beta="));

    // successive maxima above 1 mm (the amplitude has fallen by 500 at most)
    std::vector<std::pair<double, double>> peaks = Peaks(dir / row[5]);
    while (!peaks.empty() && peaks.back().second < 1e-3) peaks.pop_back();
    ASSERT_GE(peaks.size(), 3u);
    const double beta = betas[r];
    const double sigma = beta * w, period = 1 / std::sqrt(1 - beta * beta);
    for (std::size_t k = 0; k + 1 < peaks.size(); ++k) {
      const double dt = peaks[k + 1].first - peaks[k].first;
      const double rate = std::log(peaks[k].second / peaks[k + 1].second) / dt;
      EXPECT_NEAR(dt, period, 1e-5 * period) << "peak " << k;
      EXPECT_NEAR(rate, sigma, 1e-4 * sigma) << "peak " << k;
    }
  }
  // the overlay (Fig. 7.2): every run's file in every panel, labelled by its value
  std::ifstream script_file(dir / "damping_ratio.sweep.png.gp");
  std::stringstream script;
  script << script_file.rdbuf();
  for (int r = 0; r < 3; ++r) {
    const std::string file = summary[r + 1][5];
    std::size_t uses = 0;
    for (std::size_t at = script.str().find("'" + file + "' using 1:"); at != std::string::npos;
         at = script.str().find("'" + file + "' using 1:", at + 1))
      ++uses;
    EXPECT_EQ(uses, 2u) << file;  // two groups: position, spring force
  }
  EXPECT_THAT(script.str(), HasSubstr("title 'beta=0.05'"));
  EXPECT_THAT(o.out, HasSubstr("damping_ratio.sweep.png (every run over one another)"));
}

// Figures per row against the closed form of the first trough,
//   z_min = -0.5 exp(-pi beta / sqrt(1 - beta^2)) at t = Td / 2,
// and runs starved of steps (max_steps = 1 or 10 per output interval) as
// failed rows with their error; the sweep goes on and exits 1.
TEST(SweepTest, FiguresAndFailedRows) {
  const fs::path diagram = DampingRatioWithReport();
  const fs::path dir = FreshDir("figures");
  const Outcome o =
      Mechflow("sweep " + diagram.string() + " --vary beta=0.1,0.3 --vary steps=500000,10 --out " + dir.string());
  EXPECT_EQ(o.exit_code, 1) << o.err;
  EXPECT_THAT(o.err, HasSubstr("run 2/4 (beta=0.1, steps=10): failed at t = "));
  EXPECT_THAT(o.out, HasSubstr("2 ok, 2 failed"));

  const auto summary = ReadCsv(dir / "damping_ratio.sweep.csv");
  ASSERT_EQ(summary.size(), 5u);
  EXPECT_EQ(summary[0], (std::vector<std::string>{"run", "beta", "steps", "status", "t_reached", "error", "results",
                                                  "lowest z [m]", "lowest z time [s]"}));
  for (int r = 1; r <= 4; ++r) {
    const auto& row = summary[r];
    SCOPED_TRACE("row " + std::to_string(r));
    ASSERT_EQ(row.size(), 9u);
    const double beta = std::stod(row[1]);
    EXPECT_EQ(beta, r <= 2 ? 0.1 : 0.3);  // cartesian order, the last --vary fastest
    EXPECT_EQ(row[2], r % 2 ? "500000" : "10");
    ASSERT_TRUE(fs::exists(dir / row[6])) << row[6];  // written also after a failure
    if (r % 2) {
      EXPECT_EQ(row[3], "ok");
      EXPECT_EQ(std::stod(row[4]), 10.0);
      const double root = std::sqrt(1 - beta * beta);
      const double z_min = -0.5 * std::exp(-std::numbers::pi * beta / root), t_min = 0.5 / root;
      EXPECT_NEAR(std::stod(row[7]), z_min, 1e-6 * std::abs(z_min));
      EXPECT_NEAR(std::stod(row[8]), t_min, 1e-6);
    } else {
      EXPECT_EQ(row[3], "failed");
      EXPECT_LT(std::stod(row[4]), 0.005);  // within the first output interval
      EXPECT_THAT(row[5], HasSubstr("CV_TOO_MUCH_WORK"));
      // the figure up to the failure: still near the release point
      EXPECT_GT(std::stod(row[7]), 0.49);
    }
  }
}

// A value the model refuses is a failed row (nothing ran, no results), not
// bad input: the other runs go on.
TEST(SweepTest, RefusedValueIsAFailedRow) {
  const fs::path dir = FreshDir("refused");
  const Outcome o = Mechflow("sweep " + kDampingRatio + " --vary mass=-1,1000 --t-end 1 --out " + dir.string());
  EXPECT_EQ(o.exit_code, 1);
  EXPECT_THAT(o.err, HasSubstr("run 1/2 (mass=-1): failed: "));
  EXPECT_THAT(o.err, HasSubstr("damping_ratio.xml:14: body 'Box': mass must be a positive number"));
  const auto summary = ReadCsv(dir / "damping_ratio.sweep.csv");
  ASSERT_EQ(summary.size(), 3u);
  EXPECT_EQ(summary[1][2], "failed");
  EXPECT_EQ(summary[1][3], "");  // no t reached: it never started
  EXPECT_THAT(summary[1][4], HasSubstr("mass must be a positive number"));
  EXPECT_EQ(summary[1][5], "");
  EXPECT_EQ(summary[2][2], "ok");
  EXPECT_EQ(std::stod(summary[2][3]), 1.0);
}

// Bad --vary input stops the sweep before any run: exit 2, one clear message,
// no files.
TEST(SweepTest, BadVaryIsBadInput) {
  struct Case {
    std::string args, message;
  };
  const std::vector<Case> cases = {
      {"--vary betta=0.1,0.2", "--vary betta: " + kDampingRatio + " has no identifier 'betta' (did you mean 'beta'?)"},
      {"--vary cdiss=1,2", "--vary cdiss: identifier 'cdiss' (" + kDampingRatio +
                               ":11) is derived (= 2*beta*sqrt(mass*cstiff))"},
      {"--vary beta=0.1,abc", "--vary beta: 'abc' is not a number"},
      {"--vary beta=0.1,inf", "--vary beta: 'inf' is not a finite number"},
      {"--vary beta=", "--vary expects NAME=V1,V2,..., got 'beta='"},
      {"--vary beta=0.1 --vary BETA=0.2", "--vary BETA: identifier 'beta' is varied twice"},
      {"--vary beta=0.1 --set beta=0.2", "--vary beta: identifier 'beta' is also given by --set"},
      {"--jobs 0 --vary beta=0.1", "--jobs: '0' is not a whole number from 1 to 4096"},
      {"", "mechflow sweep needs at least one --vary NAME=V1,V2,..."},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.args);
    const fs::path dir = FreshDir("bad");
    const Outcome o = Mechflow("sweep " + kDampingRatio + " " + c.args + " --out " + dir.string());
    EXPECT_EQ(o.exit_code, 2);
    EXPECT_THAT(o.err, HasSubstr(c.message));
    EXPECT_FALSE(fs::exists(dir));
  }
}

TEST(SweepTest, AStarInANameStandsForEveryIndex) {
  EXPECT_TRUE(MatchesVaryPattern("s[*].mu", "S[12].MU"));
  EXPECT_TRUE(MatchesVaryPattern("chain.s[*].d[*].c", "chain.s[0].d[3].c"));
  for (const char* other : {"s[].mu", "s[1a].mu", "s.mu", "s[1].mu.x", "s[1]mu", "s[1].m", "t[1].mu"})
    EXPECT_FALSE(MatchesVaryPattern("s[*].mu", other)) << other;
  EXPECT_EQ(AsVaryPattern("chain.s[2].d[10].c"), "chain.s[*].d[*].c");
}

// --vary s[*].mu sets every s[k].mu to the run's value; the table, the
// terminal and the file names show the name as written.
TEST(SweepTest, APatternVariesEveryMatchingIdentifierAlike) {
  const fs::path dir = FreshDir("pattern");
  fs::create_directories(dir);
  // s[0].mu, s[1].mu and t[0].mu (= 2*k) are the parameters of subsystem instances
  std::ofstream(dir / "fr.xml") << R"(<subsystem name="fr">
  <parameter name="mu" default="0.1"/>
  <output name="y"/>
  <blocks><block type="constant" name="c" value="mu"/></blocks>
  <connections><connect from="c.y" to="y"/></connections>
</subsystem>
)";
  const fs::path diagram = dir / "p.xml";
  std::ofstream(diagram) << R"(<diagram name="p">
  <identifiers><identifier name="k" value="1"/></identifiers>
  <blocks>
    <block type="subsystem" name="s" src="fr.xml" count="2"/>
    <block type="subsystem" name="t" src="fr.xml" count="1"><param name="mu" value="2*k"/></block>
  </blocks>
  <solver t_end="0.1"/>
  <output interval="0.1"><log signal="s[0].c.y"/><log signal="s[1].c.y"/><log signal="t[0].c.y"/></output>
</diagram>
)";
  const fs::path out = dir / "out";
  const Outcome o = Mechflow("sweep " + diagram.string() + " --vary 's[*].mu=0.2,0.3' --jobs 1 --out " + out.string());
  ASSERT_EQ(o.exit_code, 0) << o.err;
  EXPECT_THAT(o.out, HasSubstr("run 2/2 (s[*].mu=0.3): ok"));
  EXPECT_EQ(ReadFile(out / "p.sweep.csv"), "run,s[*].mu,status,t_reached,error,results\n"
                                           "1,0.2,ok,0.1,,p.run1.s[*].mu=0.2.csv\n"
                                           "2,0.3,ok,0.1,,p.run2.s[*].mu=0.3.csv\n");
  EXPECT_EQ(ReadFile(out / "p.run2.s[*].mu=0.3.csv"), "time,s[0].c.y,s[1].c.y,t[0].c.y\n0,0.3,0.3,2\n0.1,0.3,0.3,2\n");

  struct Case {
    std::string args, message;
  };
  const std::vector<Case> cases = {
      {"--vary 's[*].muu=1'", "--vary s[*].muu: " + diagram.string() +
                                  " has no identifier 's[*].muu' for any index ([*] stands for [0], [1], ...) "
                                  "(did you mean 's[*].mu'?)"},
      {"--vary 't[*].mu=1'", "--vary t[*].mu: identifier 't[0].mu' (" + diagram.string() + ":5) is derived (= 2*k)"},
      {"--vary 's[*].mu=1' --vary 'S[1].MU=2'", "--vary S[1].MU: identifier 's[1].mu' is varied twice"},
      {"--vary 's[*].mu=1' --set 's[0].mu=2'", "--vary s[*].mu: identifier 's[0].mu' is also given by --set"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.args);
    const Outcome bad = Mechflow("sweep " + diagram.string() + " " + c.args + " --out " + (dir / "bad").string());
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_THAT(bad.err, HasSubstr(c.message));
  }
}

// Every file of a sweep, by name.
std::map<std::string, std::string> Files(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::directory_iterator(dir)) files[e.path().filename().string()] = ReadFile(e.path());
  return files;
}

// Runs on two threads give the same bytes as one after another: the workers
// share nothing that a run changes.
TEST(SweepTest, TwoJobsEqualOneJob) {
  const fs::path diagram = DampingRatioWithReport();
  const std::string args = "sweep " + diagram.string() + " --vary beta=0.05,0.1,0.2,0.4 --vary steps=500000,10 ";
  const fs::path one = FreshDir("jobs1"), two = FreshDir("jobs2");
  EXPECT_EQ(Mechflow(args + "--jobs 1 --out " + one.string()).exit_code, 1);
  EXPECT_EQ(Mechflow(args + "--jobs 2 --out " + two.string()).exit_code, 1);
  const auto a = Files(one), b = Files(two);
  EXPECT_EQ(a.size(), 12u);  // 8 runs, the summary, the overlay plot and its script, .mechflow-outputs
  EXPECT_TRUE(a == b);
}

// A sweep of a diagram with a Lua control script (the sampled PD controller):
// each run's Lua state is its own, so two threads give the bytes of one, and
// a run's results are those of `mechflow run --set` with the same values.
TEST(SweepTest, ControlScriptsOnThreadsEqualSingleRuns) {
  const std::string diagram = std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/pendulum_pd_control.xml";
  const std::string args = "sweep " + diagram + " --vary dist=2,8 --vary period=0.01,0.02 ";
  const fs::path one = FreshDir("pd1"), two = FreshDir("pd2"), single = FreshDir("pd_run");
  ASSERT_EQ(Mechflow(args + "--jobs 1 --out " + one.string()).exit_code, 0);
  ASSERT_EQ(Mechflow(args + "--jobs 2 --out " + two.string()).exit_code, 0);
  const auto a = Files(one), b = Files(two);
  EXPECT_EQ(a.size(), 8u);  // 4 runs, the summary, the overlay plot and its script, .mechflow-outputs
  EXPECT_TRUE(a == b);
  ASSERT_EQ(Mechflow("run " + diagram + " --set dist=8 --set period=0.02 --out " + single.string()).exit_code, 0);
  EXPECT_EQ(a.at("pendulum_pd_control.run4.dist=8.period=0.02.csv"),
            ReadFile(single / "pendulum_pd_control.csv"));
}

// A run its control script stops (sim:stop) is not a failure: status
// "stopped", the reason in the error column, exit 0.
TEST(SweepTest, StoppedRunIsNotAFailure) {
  std::string xml = ReadFile(kDampingRatio);
  xml.replace(xml.find("<identifier name=\"beta\""), 0, "<identifier name=\"t_stop\" value=\"100\"/>\n    ");
  xml.replace(xml.find("<solver"), 0,
              "<script>\n    function step(sim)\n      if sim.t >= sim:get(\"t_stop\") then sim:stop(\"enough\") end\n"
              "    end\n  </script>\n  ");
  const fs::path diagram = fs::path(::testing::TempDir()) / ("damping_stop_" + std::to_string(getpid()) + ".xml");
  std::ofstream(diagram) << xml;
  const fs::path dir = FreshDir("stop");
  const Outcome o = Mechflow("sweep " + diagram.string() + " --vary t_stop=2,100 --out " + dir.string());
  EXPECT_EQ(o.exit_code, 0) << o.err;
  EXPECT_THAT(o.out, HasSubstr("run 1/2 (t_stop=2): stopped by the control script at t = 2 s: enough"));
  const auto summary = ReadCsv(dir / "damping_ratio.sweep.csv");
  ASSERT_EQ(summary.size(), 3u);
  EXPECT_EQ(summary[1][2], "stopped");
  EXPECT_EQ(std::stod(summary[1][3]), 2.0);  // the first output time at or after t_stop
  EXPECT_EQ(summary[1][4], "enough");
  EXPECT_EQ(summary[2][2], "ok");
  EXPECT_EQ(std::stod(summary[2][3]), 10.0);
}

// mpirun -n 2: rank 0 writes the summary of both ranks' runs, byte for byte
// the threaded one's; each rank writes its own runs' results.
TEST(SweepTest, TwoMpiRanksEqualThreads) {
#ifndef MECHFLOW_MPIEXEC
  GTEST_SKIP() << "built without MECHFLOW_MPI";
#else
  // root in CI; two ranks may exceed the cores; shared memory between the
  // ranks only (containers often have no usable network). Under the
  // sanitizers, no leak check in the ranks: OpenMPI's components leak at
  // MPI_Finalize (120 KB in 3300 allocations, from modules LeakSanitizer
  // cannot name for a suppression); the threaded sweeps check mechflow's own.
  std::string prefix = "env OMPI_MCA_btl=self,vader OMPI_MCA_btl_vader_single_copy_mechanism=none "
                       "ASAN_OPTIONS=\"${ASAN_OPTIONS}:detect_leaks=0\" " +
                       std::string(MECHFLOW_MPIEXEC) + " -n 2 --oversubscribe " +
                       (getuid() == 0 ? "--allow-run-as-root " : "");
  const Outcome probe = mechflow::testing::RunMechflow("--version", prefix);
  if (probe.exit_code != 0 || probe.out != "mechflow 0.1.0\nmechflow 0.1.0\n")
    GTEST_SKIP() << "mpirun cannot start two processes here (exit " << probe.exit_code << "): " << probe.err;

  const fs::path diagram = DampingRatioWithReport();
  const std::string args = "sweep " + diagram.string() + " --vary beta=0.05,0.1,0.2 --vary steps=500000,10 ";
  const fs::path threads = FreshDir("threads"), ranks = FreshDir("ranks");
  const Outcome threaded = Mechflow(args + "--jobs 2 --out " + threads.string());
  const Outcome mpi = mechflow::testing::RunMechflow(args + "--out " + ranks.string(), prefix);
  EXPECT_EQ(threaded.exit_code, 1);
  EXPECT_EQ(mpi.exit_code, 1) << mpi.err;
  EXPECT_THAT(mpi.out, HasSubstr(" at a time in each of 2 processes"));
  // the rows are printed once, by rank 0
  EXPECT_EQ(mpi.out.find("run 1/6"), mpi.out.rfind("run 1/6"));
  const auto a = Files(threads), b = Files(ranks);
  EXPECT_EQ(a.size(), 10u);  // 6 runs, the summary, the overlay plot and its script, .mechflow-outputs
  EXPECT_EQ(a.at("damping_ratio.sweep.csv"), b.at("damping_ratio.sweep.csv"));
  EXPECT_TRUE(a == b);
#endif
}

// The threads a sweep asks for past the first that cannot start (a process
// limit) are not started; those running are handed back to be joined.
TEST(SweepThreadsTest, AThreadThatCannotStartLeavesTheOthersRunning) {
  for (const int fails_at : {0, 1, 3}) {
    SCOPED_TRACE("the start of thread " + std::to_string(fails_at + 1) + " fails");
    std::atomic<int> ran{0};
    int starts = 0;
    std::vector<std::thread> threads = StartThreads(5, [&] { ++ran; }, [&](const std::function<void()>& worker) {
      if (starts++ == fails_at) throw std::system_error(EAGAIN, std::generic_category(), "thread");
      return std::thread(worker);
    });
    EXPECT_EQ(static_cast<int>(threads.size()), fails_at);
    EXPECT_EQ(starts, fails_at + 1);  // none tried after the failure
    for (std::thread& t : threads) t.join();
    EXPECT_EQ(ran, fails_at);
  }
  std::vector<std::thread> all = StartThreads(3, [] {}, [](const std::function<void()>& w) { return std::thread(w); });
  EXPECT_EQ(all.size(), 3u);
  for (std::thread& t : all) t.join();
}

// The same through the command: under an address-space limit that leaves
// room for two 256 MB thread stacks, a sweep asking for 6 threads runs with
// what it got, says so, and writes its summary (it ended in std::terminate).
TEST(SweepTest, ThreadsThatCannotStartAreDoneWithout) {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  GTEST_SKIP() << "a sanitizer's shadow memory does not fit an address-space limit";
#else
  // no gnuplot on the PATH: under the limit its own threads would fail (a warning instead of the plot)
  const fs::path dir = FreshDir("nothreads"), no_programs = FreshDir("no_programs");
  fs::create_directories(no_programs);
  const Outcome o = mechflow::testing::RunMechflow(
      "sweep " + kDampingRatio + " --vary beta=0.1,0.2,0.3,0.4,0.5,0.6 --t-end 1 --jobs 6 --out " + dir.string(),
      "ulimit -s 262144 && ulimit -v 1000000 && PATH=" + no_programs.string() + " ");
  EXPECT_EQ(o.exit_code, 0) << o.err;
  EXPECT_THAT(o.err, ::testing::ContainsRegex("mechflow: could start only [1-5] of 6 threads; running with [1-5]\n"));
  const auto summary = ReadCsv(dir / "damping_ratio.sweep.csv");
  ASSERT_EQ(summary.size(), 7u);
  for (std::size_t r = 1; r < summary.size(); ++r) EXPECT_EQ(summary[r][2], "ok") << "row " << r;
#endif
}

// A Ctrl-C at the terminal while the overlay is drawn reaches gnuplot too
// (here a stand-in that sends it and fails): the summary is written, the
// plot is left out, and the exit code is the signal's, not a write error's.
TEST(SweepTest, AnInterruptWhileTheOverlayIsDrawnEndsTheSweepAsInterrupted) {
  const fs::path dir = FreshDir("overlay_int"), bin = FreshDir("fake_gnuplot");
  fs::create_directories(bin);
  std::ofstream(bin / "gnuplot") << "#!/bin/sh\nkill -INT $PPID\nexit 1\n";
  fs::permissions(bin / "gnuplot", fs::perms::owner_all);
  const Outcome o = mechflow::testing::RunMechflow(
      "sweep " + kDampingRatio + " --vary beta=0.1,0.2 --t-end 1 --out " + dir.string(),
      "PATH=" + bin.string() + ":$PATH ");
  EXPECT_EQ(o.exit_code, 130) << o.err;
  // the signal is seen while gnuplot runs, or once it has failed: either way no plot
  EXPECT_THAT(o.err, ::testing::AnyOf(HasSubstr("warning: no plot: interrupted by SIGINT"),
                                      HasSubstr("SIGINT came while gnuplot drew it")));
  EXPECT_THAT(o.out, HasSubstr("run 2/2 (beta=0.2): ok"));
  const auto summary = ReadCsv(dir / "damping_ratio.sweep.csv");
  ASSERT_EQ(summary.size(), 3u);
  EXPECT_EQ(summary[2][2], "ok");
}

}  // namespace
}  // namespace mechflow::cli::sweep_test
