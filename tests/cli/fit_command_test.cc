// `mechflow fit`: the damped oscillator's frequency and damping ratio from
// its closed-form motion written as a data file; the files it writes (the
// set file read back by `mechflow run --set-file`); bad input with file:line.
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/cli/mechflow_command.h"
#include "tests/numbers.h"

namespace mechflow {
namespace fit_command_test {

using ::testing::HasSubstr;
using testing::ReadFile;
using testing::RunMechflow;

namespace fs = std::filesystem;

const std::string kOscillator = std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/damped_oscillator_blocks.xml";

double Displacement(double t, double f, double beta) {
  const double w = 2 * mechflow::testing::kPi * f, wd = w * std::sqrt(1 - beta * beta);
  return 0.5 * std::exp(-beta * w * t) * (std::cos(wd * t) + beta * w / wd * std::sin(wd * t));
}

// x of the oscillator with f = 1.2 Hz, beta = 0.15 at 0.05 s steps to 4 s.
fs::path WriteData(const fs::path& dir, const std::string& name) {
  fs::create_directories(dir);
  std::ofstream csv(dir / name);
  csv.precision(17);
  csv << "time,x_meas\n";
  for (int i = 1; i <= 80; ++i) csv << 0.05 * i << "," << Displacement(0.05 * i, 1.2, 0.15) << "\n";
  return dir / name;
}

std::string Fit(const fs::path& data, const fs::path& out, const std::string& more = "") {
  return "fit " + kOscillator + " --data " + data.string() + " --match x.y=x_meas --free f=0.5:2 " +
         "--free beta=0.01:0.5:log --jobs 2 --out " + out.string() + " " + more;
}

TEST(FitCommandTest, FitsOscillatorAndWritesItsFiles) {
  const fs::path dir = fs::path(::testing::TempDir()) / "fit_command";
  const fs::path data = WriteData(dir, "measured.csv");
  const auto fit = RunMechflow(Fit(data, dir / "out", "--holdout " + data.string()));
  ASSERT_EQ(fit.exit_code, 0) << fit.out << fit.err;
  EXPECT_THAT(fit.out, HasSubstr("2 parameters, 1 experiment (80 measured values), Levenberg-Marquardt (Ceres)"));
  EXPECT_THAT(fit.out, HasSubstr("cost (sum of squared weighted residuals, 80 of them): before "));
  EXPECT_THAT(fit.out, HasSubstr("holdout: cost "));
  EXPECT_THAT(fit.out, HasSubstr(" runs/s)"));
  std::istringstream table(ReadFile(dir / "out" / "damped_oscillator_blocks.fit.csv"));
  std::string line;
  std::getline(table, line);
  EXPECT_EQ(line, "parameter,value,standard_error,lower,upper,at_bound");
  std::getline(table, line);
  EXPECT_THAT(line, ::testing::StartsWith("f,1.2"));  // 1.2 to the solver's accuracy
  EXPECT_NEAR(std::stod(line.substr(2)), 1.2, 1e-6);
  EXPECT_THAT(line, ::testing::EndsWith(",0.5,2,no"));
  std::getline(table, line);
  EXPECT_NEAR(std::stod(line.substr(5)), 0.15, 1e-6);
  EXPECT_THAT(ReadFile(dir / "out" / "damped_oscillator_blocks.fit.correlation.csv"),
              ::testing::StartsWith("parameter,f,beta\nf,1,"));
  EXPECT_TRUE(fs::exists(dir / "out" / "damped_oscillator_blocks.fit.data1.csv"));
  // what was printed from the table on, written
  const std::string summary = ReadFile(dir / "out" / "damped_oscillator_blocks.fit.txt");
  EXPECT_THAT(summary, ::testing::StartsWith("parameter "));
  EXPECT_THAT(fit.out, HasSubstr(summary));
  EXPECT_THAT(summary, HasSubstr("cost (sum of squared weighted residuals"));
  EXPECT_THAT(summary, HasSubstr(" runs in "));
  EXPECT_TRUE(fs::exists(dir / "out" / "damped_oscillator_blocks.fit.history.csv"));
  // the set file, as `run --set-file` reads it: the run goes through the data
  const auto run = RunMechflow("run " + kOscillator + " --set-file " +
                               (dir / "out" / "damped_oscillator_blocks.fit.set").string() + " --t-end 1 --no-plot --out " +
                               (dir / "run").string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::istringstream rows(ReadFile(dir / "run" / "damped_oscillator_blocks.csv"));
  std::getline(rows, line);
  for (int i = 0; std::getline(rows, line); ++i) {
    const double t = std::stod(line), x = std::stod(line.substr(line.find(',') + 1));
    ASSERT_NEAR(x, Displacement(t, 1.2, 0.15), 1e-6) << "t = " << t;
  }
}

TEST(FitCommandTest, BadDataNamesFileAndLine) {
  const fs::path dir = fs::path(::testing::TempDir()) / "fit_bad";
  fs::create_directories(dir);
  std::ofstream(dir / "unsorted.csv") << "time,x_meas\n0.1,0.5\n0.3,0.4\n0.2,0.3\n";
  std::ofstream(dir / "nan.csv") << "time,x_meas\n0.1,0.5\n0.2,nan\n";
  std::ofstream(dir / "late.csv") << "time,x_meas\n0.1,0.5\n\n12,0.4\n";
  auto r = RunMechflow(Fit(dir / "unsorted.csv", dir / "out"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("unsorted.csv:4: time 0.2 is not after the row before"));
  r = RunMechflow(Fit(dir / "nan.csv", dir / "out"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("nan.csv:3: 'nan' is not a finite number"));
  r = RunMechflow(Fit(dir / "late.csv", dir / "out"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("late.csv:4: time 12 is outside the run (0 to 10 s)"));
}

TEST(FitCommandTest, GuardsRefuseBeforeFitting) {
  const fs::path dir = fs::path(::testing::TempDir()) / "fit_guards";
  const fs::path data = WriteData(dir, "measured.csv");
  auto r = RunMechflow(Fit(data, dir / "out", "--free m=500:2000"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("m has no effect on x.y"));
  r = RunMechflow(Fit(data, dir / "out", "--constraint 'f<2'"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--constraint 'f<2': expected A<=B or A>=B"));
  r = RunMechflow(Fit(data, dir / "out", "--constraint 'f<=beta'"));  // starts at f = 1, beta = 0.1
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("the start values break a constraint: f=1 above beta=0.1 breaks --constraint f<=beta"));
  r = RunMechflow(Fit(data, dir / "out", "--method newton"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--method: 'newton' is not lm or derivative-free"));
  r = RunMechflow(Fit(data, dir / "out", "--free c=1:10"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("is defined by an expression"));
  r = RunMechflow(Fit(data, dir / "out", "--set f=1.1"));  // after its --data: that experiment's
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("f is a free parameter, fitted to all the data"));
}

TEST(FitCommandTest, StartOnBoundMovedInside) {
  const fs::path dir = fs::path(::testing::TempDir()) / "fit_bound";
  const fs::path data = WriteData(dir, "measured.csv");
  const auto r = RunMechflow("fit " + kOscillator + " --data " + data.string() +
                             " --match x.y=x_meas --free f=1:2 --free beta=0.05:0.5 --no-plot --out " +
                             (dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("note: the start of f, 1, is on a bound; moved inside to 1.01"));
}

// The tension mechanism's contact stiffness from a measured peak contact
// force and its time (its <report>), made by the diagram with the stiffness
// it gives (200000 N/m^2): recovered from half of it.
TEST(FitCommandTest, ContactStiffnessFromPeakForce) {
  const fs::path dir = fs::path(::testing::TempDir()) / "fit_peak";
  fs::create_directories(dir);
  const std::string diagram = std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/tension_mechanism.xml";
  const auto run = RunMechflow("run " + diagram + " --no-plot --no-animate --out " + (dir / "truth").string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::istringstream report(ReadFile(dir / "truth" / "tension_mechanism.report.csv"));
  std::string line;
  std::getline(report, line);
  std::getline(report, line);  // peak contact force,peak,m.contact_force,VALUE,N,TIME
  std::vector<std::string> f;
  for (std::size_t start = 0;;) {
    const std::size_t comma = line.find(',', start);
    f.push_back(line.substr(start, comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  ASSERT_EQ(f.size(), 6u) << line;
  std::ofstream(dir / "peak.csv") << "time,F_peak,t_peak\n0," << f[3] << "," << f[5] << "\n";
  const std::string fit = "fit " + diagram + " --set Stiffnes=100000 --data " + (dir / "peak.csv").string() +
                          " --match 'report:peak contact force=F_peak' --match 'report-time:peak contact force=t_peak:1000'"
                          " --free Stiffnes=1e4:1e6:log --no-plot --out " + (dir / "fit").string();
  const auto r = RunMechflow(fit);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_THAT(r.out, HasSubstr("1 experiment (2 measured values)"));
  EXPECT_THAT(r.out, HasSubstr("report:peak contact force: measured 285.219, start 284.848, fitted 285.219"));
  std::istringstream table(ReadFile(dir / "fit" / "tension_mechanism.fit.csv"));
  std::getline(table, line);
  std::getline(table, line);
  EXPECT_NEAR(std::stod(line.substr(line.find(',') + 1)), 200000, 1);
  // a report the diagram does not have; a figure's column that changes
  auto bad = RunMechflow("fit " + diagram + " --data " + (dir / "peak.csv").string() +
                         " --match 'report:peak force=F_peak' --free Stiffnes=1e4:1e6:log --out " + (dir / "fit").string());
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_THAT(bad.err, HasSubstr("has no <report> 'peak force'"));
  std::ofstream(dir / "two.csv") << "time,F_peak\n0,285\n0.1,286\n";
  bad = RunMechflow("fit " + diagram + " --data " + (dir / "two.csv").string() +
                    " --match 'report:peak contact force=F_peak' --free Stiffnes=1e4:1e6:log --out " + (dir / "fit").string());
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_THAT(bad.err, HasSubstr("two.csv:3: F_peak is 286, not 285 as in the first row"));
}

// The seed's ElastFriction2 element (both stiffnesses and the friction
// coefficient) from the force-displacement loop `mechflow force-analysis`
// draws of it (the reaction R over the last of 10 cycles of x = a sin(2 pi t)):
// a diagram that drives the element alike, started from other values,
// recovers the seed's 400 N/m, 100 N/m and 0.2.
TEST(FitCommandTest, ElastFriction2FromItsForceAnalysisLoop) {
  const fs::path dir = fs::path(::testing::TempDir()) / "fit_ef2";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const auto analysis = RunMechflow("force-analysis " + std::string(MECHFLOW_SOURCE_DIR) +
                                    "/diagrams/examples/elast_friction2.xml --element friction --amplitude 0.05 "
                                    "--frequency 1 --cycles 10 --samples 100 --out " + (dir / "fa").string());
  ASSERT_EQ(analysis.exit_code, 0) << analysis.err;
  // x', v, R at t = 9.005, 9.015, ... s, the first row again at the end to close the loop
  std::istringstream loop(ReadFile(dir / "fa" / "elast_friction2.force_analysis.loops.csv"));
  std::string line;
  std::getline(loop, line);
  std::vector<double> reaction;
  while (std::getline(loop, line)) reaction.push_back(std::stod(line.substr(line.rfind(',') + 1)));
  ASSERT_EQ(reaction.size(), 101u);
  std::ofstream data(dir / "loop.csv");
  data.precision(17);
  data << "time,F\n";  // the element's force, -R
  for (int k = 0; k < 100; ++k) data << 9 + (k + 0.5) / 100 << "," << -reaction[k] << "\n";
  data.close();
  std::ofstream(dir / "driven.xml") << R"xml(<diagram name="driven_ef2">
  <identifiers>
    <identifier name="cspring" value="300" unit="N/m"/><identifier name="cspring2" value="150" unit="N/m"/>
    <identifier name="ffr" value="0.3"/>
  </identifiers>
  <mechanism name="m" gravity="0 0 -9.81">
    <body name="Box" mass="10" inertia="1 1 1"/>
    <joint name="jBox" type="generalized" body1="Base0" body2="Box">
      <et type="tc" axis="1 0 0" value="1"/><et type="tt" axis="1 0 0" value="0.05*sin(2*pi*t)"/>
    </joint>
    <force name="friction" type="elastic_friction2" body1="Base0" point1="0 0 0" body2="Box"
           c1="cspring" c2="cspring2" mu="ffr" mu0="ffr" l0="1"/>
    <sensor name="force" kind="element" element="friction"/>
  </mechanism>
  <solver t_end="10" rtol="1e-8" atol="1e-10"/>
</diagram>)xml";
  const auto r = RunMechflow("fit " + (dir / "driven.xml").string() + " --data " + (dir / "loop.csv").string() +
                             " --match m.force=F --free cspring=100:1000:log --free cspring2=30:300:log "
                             "--free ffr=0.05:0.6 --no-plot --out " + (dir / "fit").string());
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  std::istringstream table(ReadFile(dir / "fit" / "driven_ef2.fit.csv"));
  std::getline(table, line);
  for (const double truth : {400.0, 100.0, 0.2}) {
    std::getline(table, line);
    EXPECT_NEAR(std::stod(line.substr(line.find(',') + 1)), truth, 1e-6 * truth) << line;
  }
}

// mpirun -n 2: the processes share each round of runs and write the files of
// the threaded fit, byte for byte (rank 0 alone writes).
TEST(FitCommandTest, TwoMpiRanksEqualThreads) {
#ifndef MECHFLOW_MPIEXEC
  GTEST_SKIP() << "built without MECHFLOW_MPI";
#else
  // as the sweep's test: shared memory between the ranks only, no leak check in them
  const std::string prefix = "env OMPI_MCA_btl=self,vader OMPI_MCA_btl_vader_single_copy_mechanism=none "
                             "ASAN_OPTIONS=\"${ASAN_OPTIONS}:detect_leaks=0\" " +
                             std::string(MECHFLOW_MPIEXEC) + " -n 2 --oversubscribe " +
                             (getuid() == 0 ? "--allow-run-as-root " : "");
  const auto probe = RunMechflow("--version", prefix);
  if (probe.exit_code != 0 || probe.out != "mechflow 0.1.0\nmechflow 0.1.0\n")
    GTEST_SKIP() << "mpirun cannot start two processes here (exit " << probe.exit_code << "): " << probe.err;
  const fs::path dir = fs::path(::testing::TempDir()) / "fit_mpi";
  fs::remove_all(dir);
  const fs::path data = WriteData(dir, "measured.csv");
  const auto threads = RunMechflow(Fit(data, dir / "threads", "--no-plot"));
  const auto mpi = RunMechflow(Fit(data, dir / "ranks", "--no-plot --jobs 1"), prefix);
  ASSERT_EQ(threads.exit_code, 0) << threads.err;
  ASSERT_EQ(mpi.exit_code, 0) << mpi.err;
  EXPECT_THAT(mpi.out, HasSubstr("1 run at a time in each of 2 processes"));
  EXPECT_EQ(mpi.out.find("parameter "), mpi.out.rfind("parameter "));  // printed once
  for (const char* name : {"fit.csv", "fit.set", "fit.correlation.csv", "fit.history.csv", "fit.data1.csv"})  // not fit.txt: times differ
    EXPECT_EQ(ReadFile(dir / "threads" / ("damped_oscillator_blocks." + std::string(name))),
              ReadFile(dir / "ranks" / ("damped_oscillator_blocks." + std::string(name))))
        << name;
#endif
}

}  // namespace fit_command_test
}  // namespace mechflow
