// `mechflow modes` run as a user would: the table, NAME.modes.csv, --equilibrium,
// the output folder, help and exit codes, on block diagrams.

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace mechflow::cli::modes_command_test {  // names of its own: the files of its folder are compiled together
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;
namespace fs = std::filesystem;

constexpr double kPi = 3.14159265358979323846;

struct Outcome {
  int exit_code = -1;
  std::string out, err;
};

std::string ReadFile(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A fresh folder for one test (CTest runs test processes in parallel).
fs::path FreshDir(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("mechflow_modes_" + std::to_string(getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// Runs `mechflow ARGS` in the folder `cwd` with stdout and stderr captured.
Outcome Mechflow(const std::string& args, const fs::path& cwd) {
  const std::string command = "cd '" + cwd.string() + "' && " + std::string(MECHFLOW_BINARY) + " " + args + " >" +
                              (cwd / "stdout").string() + " 2>" + (cwd / "stderr").string() + " </dev/null";
  const int status = std::system(command.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, ReadFile(cwd / "stdout"), ReadFile(cwd / "stderr")};
}

std::string Example(const std::string& name) {
  return std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/" + name;
}

fs::path WriteDiagram(const fs::path& dir, const std::string& name, const std::string& xml) {
  const fs::path path = dir / name;
  std::ofstream(path) << xml;
  return path;
}

struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;
  int Column(const std::string& name) const {
    const auto it = std::find(header.begin(), header.end(), name);
    return it == header.end() ? -1 : static_cast<int>(it - header.begin());
  }
};

Csv ReadCsv(const fs::path& path) {
  Csv csv;
  std::ifstream in(path);
  std::string line;
  if (std::getline(in, line)) {
    std::stringstream fields(line);
    for (std::string f; std::getline(fields, f, ',');) csv.header.push_back(f);
  }
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::stringstream fields(line);
    for (std::string f; std::getline(fields, f, ',');) row.push_back(std::stod(f));
    csv.rows.push_back(row);
  }
  return csv;
}

// The value printed for `state` in the "linearised at" table of stdout.
double PrintedState(const std::string& out, const std::string& state) {
  std::istringstream lines(out);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream fields(line);
    std::string name;
    double value = 0.0;
    if (fields >> name && name == state && fields >> value) return value;
  }
  ADD_FAILURE() << "no state " << state << " in\n" << out;
  return NAN;
}

// m x'' = -c x - d v - m g from blocks, started unloaded (x = 0) and moving.
const char* kHangingMass =
    "<?xml version=\"1.0\"?>\n<diagram name=\"hanging_mass\">\n<identifiers>\n"
    "<identifier name=\"m\" value=\"2\"/>\n<identifier name=\"c\" value=\"800\"/>\n"
    "<identifier name=\"d\" value=\"4\"/>\n<identifier name=\"g\" value=\"9.81\"/>\n"
    "</identifiers>\n<blocks>\n"
    "<block type=\"integrator\" name=\"x\" initial=\"0\"/>\n"
    "<block type=\"integrator\" name=\"v\" initial=\"0.3\"/>\n"
    "<block type=\"gain\" name=\"spring\" k=\"-c/m\"/>\n"
    "<block type=\"gain\" name=\"damper\" k=\"-d/m\"/>\n"
    "<block type=\"constant\" name=\"gravity\" value=\"-g\"/>\n"
    "<block type=\"sum\" name=\"a\" signs=\"+++\"/>\n"
    "</blocks>\n<connections>\n"
    "<connect from=\"x.y\" to=\"spring.u\"/><connect from=\"v.y\" to=\"damper.u\"/>\n"
    "<connect from=\"spring.y\" to=\"a.u1\"/><connect from=\"damper.y\" to=\"a.u2\"/>\n"
    "<connect from=\"gravity.y\" to=\"a.u3\"/>\n"
    "<connect from=\"a.y\" to=\"v.u\"/><connect from=\"v.y\" to=\"x.u\"/>\n"
    "</connections>\n</diagram>\n";

TEST(ModesCommandTest, DampedOscillatorBlocks) {
  const fs::path dir = FreshDir("damped");
  const Outcome r = Mechflow("modes " + Example("damped_oscillator_blocks.xml") + " --out results", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_THAT(r.out, HasSubstr("linearised at the initial state, t = 0 s"));
  EXPECT_THAT(r.out, HasSubstr("f damped [Hz]   f natural [Hz]   damping ratio   Re lambda [1/s]   Im lambda [rad/s]"));
  EXPECT_THAT(r.out, HasSubstr("       0.994987         1.000000        0.100000"));
  EXPECT_THAT(r.out, HasSubstr("oscillating"));
  EXPECT_EQ(PrintedState(r.out, "x.x"), 0.5);
  EXPECT_THAT(r.out, HasSubstr("coordinate"));
  EXPECT_THAT(r.out, HasSubstr("wrote " + (dir / "results" / "damped_oscillator_blocks.modes.csv").string() + " (1 mode)"));

  const Csv csv = ReadCsv(dir / "results" / "damped_oscillator_blocks.modes.csv");
  EXPECT_EQ(csv.header, (std::vector<std::string>{"mode", "frequency_hz", "natural_frequency_hz", "damping_ratio",
                                                  "lambda_re", "lambda_im", "x.x", "v.x"}));
  ASSERT_EQ(csv.rows.size(), 1u);
  const auto& row = csv.rows[0];
  EXPECT_EQ(row[0], 1);
  EXPECT_NEAR(row[1], 0.994987, 1e-6);
  EXPECT_NEAR(row[2], 1.0, 1e-6);
  EXPECT_NEAR(row[3], 0.1, 1e-6);
  EXPECT_NEAR(row[4], -0.2 * kPi, 1e-6);
  EXPECT_NEAR(row[5], 2 * kPi * std::sqrt(0.99), 1e-6);
  EXPECT_EQ(row[csv.Column("x.x")], 1.0);  // the coordinate carries the shape
}

TEST(ModesCommandTest, ThreeMassesBlocksInTheCurrentFolderByDefault) {
  const fs::path dir = FreshDir("three_masses");
  const Outcome r = Mechflow("modes " + Example("three_masses_blocks.xml"), dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Csv csv = ReadCsv(dir / "three_masses_blocks.modes.csv");
  ASSERT_EQ(csv.rows.size(), 3u);
  const double expected[3] = {17.6613, 43.8189, 67.2512};
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(csv.rows[k][1], expected[k], 1e-4);
    EXPECT_NEAR(csv.rows[k][2], expected[k], 1e-4);
    EXPECT_EQ(csv.rows[k][3], 0.0);
  }
  // lowest mode: all masses in phase, the top one moving most
  const auto& first = csv.rows[0];
  EXPECT_EQ(first[csv.Column("x3.x")], 1.0);
  EXPECT_GT(first[csv.Column("x1.x")], 0.0);
  EXPECT_LT(first[csv.Column("x1.x")], first[csv.Column("x2.x")]);
  EXPECT_NEAR(first[csv.Column("v3.x")], 0.0, 1e-9);  // an undamped mode's rates are imaginary
  EXPECT_THAT(r.out, HasSubstr("mode 1      mode 2      mode 3"));
}

TEST(ModesCommandTest, EquilibriumOfAHangingMass) {
  const fs::path dir = FreshDir("hanging");
  const fs::path diagram = WriteDiagram(dir, "hanging_mass.xml", kHangingMass);
  const double m = 2, c = 800, g = 9.81;

  const Outcome initial = Mechflow("modes hanging_mass.xml --out initial", dir);
  ASSERT_EQ(initial.exit_code, 0) << initial.err;
  EXPECT_EQ(PrintedState(initial.out, "x.x"), 0.0);

  const Outcome r = Mechflow("modes hanging_mass.xml --equilibrium --out eq", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("linearised at the static equilibrium, t = 0 s (found in "));
  EXPECT_NEAR(PrintedState(r.out, "x.x"), -m * g / c, 1e-8);  // printed to 9 digits
  EXPECT_NEAR(PrintedState(r.out, "v.x"), 0.0, 1e-12);
  // gravity only shifts a linear spring: the same mode at both points
  const Csv at_rest = ReadCsv(dir / "eq" / "hanging_mass.modes.csv");
  const Csv at_start = ReadCsv(dir / "initial" / "hanging_mass.modes.csv");
  ASSERT_EQ(at_rest.rows.size(), 1u);
  EXPECT_NEAR(at_rest.rows[0][2], std::sqrt(c / m) / (2 * kPi), 1e-9);
  EXPECT_NEAR(at_rest.rows[0][1], at_start.rows[0][1], 1e-12);

  // --set reaches the diagram: a stiffer spring sags less
  const Outcome stiff = Mechflow("modes hanging_mass.xml --equilibrium --set c=1600 --out stiff", dir);
  ASSERT_EQ(stiff.exit_code, 0) << stiff.err;
  EXPECT_NEAR(PrintedState(stiff.out, "x.x"), -m * g / 1600, 1e-8);
}

TEST(ModesCommandTest, RealModesListTheirDecayRate) {
  // x' = -4 x: one real mode, decaying at 4 1/s
  const fs::path dir = FreshDir("decay");
  WriteDiagram(dir, "decay.xml",
               "<diagram>\n<blocks>\n<block type=\"integrator\" name=\"x\" initial=\"1\"/>\n"
               "<block type=\"gain\" name=\"k\" k=\"-4\"/>\n</blocks>\n<connections>\n"
               "<connect from=\"x.y\" to=\"k.u\"/><connect from=\"k.y\" to=\"x.u\"/>\n"
               "</connections>\n</diagram>\n");
  const Outcome r = Mechflow("modes decay.xml", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("decaying at 4 1/s (time constant 0.25 s)"));
  const Csv csv = ReadCsv(dir / "decay.modes.csv");  // named after the diagram (its file's stem)
  ASSERT_EQ(csv.rows.size(), 1u);
  EXPECT_EQ(csv.rows[0][1], 0.0);
  EXPECT_NEAR(csv.rows[0][4], -4.0, 1e-9);
  EXPECT_EQ(csv.rows[0][3], 1.0);
}

TEST(ModesCommandTest, NoEquilibriumExitsWithOne) {
  const fs::path dir = FreshDir("drift");
  WriteDiagram(dir, "drift.xml",
               "<diagram>\n<blocks>\n<block type=\"integrator\" name=\"x\" initial=\"0\"/>\n"
               "<block type=\"constant\" name=\"one\" value=\"1\"/>\n</blocks>\n"
               "<connections>\n<connect from=\"one.y\" to=\"x.u\"/>\n</connections>\n</diagram>\n");
  const Outcome r = Mechflow("modes drift.xml --equilibrium", dir);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, StartsWith("simulation failed: no static equilibrium found: Newton stalled"));
  EXPECT_THAT(r.err, HasSubstr("the largest rate is 1 (state 'x.x')"));
  EXPECT_FALSE(fs::exists(dir / "drift.modes.csv"));
  // without --equilibrium the same diagram has one rigid-body mode
  const Outcome plain = Mechflow("modes drift.xml", dir);
  EXPECT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_THAT(plain.out, HasSubstr("rigid-body"));
}

TEST(ModesCommandTest, BadInputExitsWithTwo) {
  const fs::path dir = FreshDir("bad");
  WriteDiagram(dir, "stateless.xml",
               "<diagram>\n<blocks>\n<block type=\"constant\" name=\"one\" value=\"1\"/>\n</blocks>\n</diagram>\n");
  const Outcome stateless = Mechflow("modes stateless.xml", dir);
  EXPECT_EQ(stateless.exit_code, 2);
  EXPECT_EQ(stateless.err, "stateless.xml: the diagram has no continuous states; nothing to analyse\n");

  const Outcome missing = Mechflow("modes missing.xml", dir);
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_THAT(missing.err, HasSubstr("missing.xml"));

  EXPECT_EQ(Mechflow("modes", dir).exit_code, 2);
  const Outcome typo = Mechflow("modes " + Example("damped_oscillator_blocks.xml") + " --equilibirum", dir);
  EXPECT_EQ(typo.exit_code, 2);
  EXPECT_THAT(typo.err, HasSubstr("unknown option '--equilibirum' (did you mean '--equilibrium'?)"));
  EXPECT_EQ(Mechflow("run " + Example("damped_oscillator_blocks.xml") + " --equilibrium", dir).exit_code, 2);
  EXPECT_THAT(Mechflow("modes " + Example("damped_oscillator_blocks.xml") + " --set nosuch=1", dir).err,
              HasSubstr("nosuch"));

  // an output folder that cannot be created
  std::ofstream(dir / "file") << "x";
  const Outcome blocked = Mechflow("modes " + Example("damped_oscillator_blocks.xml") + " --out file/sub", dir);
  EXPECT_EQ(blocked.exit_code, 2);
  EXPECT_THAT(blocked.err, StartsWith("cannot create the output folder 'file/sub'"));
}

// A diagram with switching elements says which mode each was linearised in
// (a user must see that a locked friction damper is not a free motion).
TEST(ModesCommandTest, SwitchingElementsAreNamedWithTheirModes) {
  const fs::path dir = FreshDir("switching");
  const Outcome car = Mechflow("modes " + Example("quarter_car.xml"), dir);
  ASSERT_EQ(car.exit_code, 0) << car.err;
  EXPECT_THAT(car.out, HasSubstr("switching elements, linearised in their modes at this state"));
  EXPECT_THAT(car.out, HasSubstr("car.damper: stuck, held exactly: its relative motion is locked"));
  // locked: wheel and body move as one on the tyre, sqrt(k_tyre / 440 kg) / 2 pi
  char f[32];
  std::snprintf(f, sizeof f, "%.6f", std::sqrt(2e5 / 440) / (2 * kPi));
  EXPECT_THAT(car.out, HasSubstr(f));
  const Outcome leaf = Mechflow("modes " + Example("leaf_spring.xml"), dir);
  EXPECT_THAT(leaf.out, HasSubstr("m.friction: stuck on its stick spring"));
  EXPECT_THAT(leaf.out, HasSubstr("friction_force: regularised near rest (v = 0"));
  const Outcome belt = Mechflow("modes " + Example("stick_slip_blocks.xml"), dir);
  EXPECT_THAT(belt.out, HasSubstr("friction: sliding (v = -0.1)"));
  // none in a smooth diagram
  EXPECT_THAT(Mechflow("modes " + Example("frequencies.xml"), dir).out,
              ::testing::Not(HasSubstr("switching elements")));
}

TEST(ModesCommandTest, Help) {
  const fs::path dir = FreshDir("help");
  const Outcome help = Mechflow("help modes", dir);
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_THAT(help.out, StartsWith("usage: mechflow modes FILE"));
  EXPECT_THAT(help.out, HasSubstr("--equilibrium"));
  EXPECT_THAT(help.out, HasSubstr("Exit codes: 0 done, 1 no equilibrium found"));
  EXPECT_EQ(Mechflow("modes --help", dir).out, help.out);
  EXPECT_THAT(Mechflow("--help", dir).out, HasSubstr("modes   natural frequencies"));
}

}  // namespace
}  // namespace mechflow::cli::modes_command_test
