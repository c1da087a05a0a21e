// Command-line conventions users bring from other tools (so habits work, not surprise):
// --opt=value, solver and output settings on the command line, ranges for
// --vary, --quiet, and a usage error that shows the command's own usage.
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli/arguments.h"
#include "tests/cli/mechflow_command.h"

namespace mechflow::cli {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
namespace fs = std::filesystem;

TEST(CommandLineTest, OptionEqualsValueReadsAsOptionThenValue) {
  const Arguments a = ParseArguments({"run", "d.xml", "--set=c=2", "--t-end=3", "--rtol", "1e-9", "--atol=1e-12",
                                      "--interval=0.5", "--results=r.csv", "--out=o", "--quiet"});
  ASSERT_EQ(a.overrides.size(), 1u);
  EXPECT_EQ(a.overrides[0].first, "c");
  EXPECT_EQ(a.overrides[0].second, 2.0);
  EXPECT_EQ(*a.t_end, 3.0);
  EXPECT_EQ(*a.rtol, 1e-9);
  EXPECT_EQ(*a.atol, 1e-12);
  EXPECT_EQ(*a.interval, 0.5);
  EXPECT_EQ(*a.results, "r.csv");
  EXPECT_EQ(a.out_dir, "o");
  EXPECT_TRUE(a.quiet);
}

TEST(CommandLineTest, VaryRanges) {
  const Arguments lin = ParseArguments({"sweep", "d.xml", "--vary", "beta=0.05:0.2:4"});
  EXPECT_THAT(lin.vary[0].second, ElementsAre(0.05, 0.1, 0.15, 0.2));
  const Arguments log = ParseArguments({"sweep", "d.xml", "--vary=k=1:100:3:log"});
  EXPECT_THAT(log.vary[0].second, ElementsAre(1.0, 10.0, 100.0));
  EXPECT_THROW(ParseArguments({"sweep", "d.xml", "--vary", "k=1:2"}), UsageError);
  EXPECT_THROW(ParseArguments({"sweep", "d.xml", "--vary", "k=0:2:3:log"}), UsageError);
  EXPECT_THROW(ParseArguments({"sweep", "d.xml", "--vary", "k=1:2:1.5"}), UsageError);
  EXPECT_THROW(ParseArguments({"run", "d.xml", "--quiet", "--verbose"}), UsageError);
}

TEST(CommandLineTest, RunSettingsQuietAndUsage) {
  const fs::path out = fs::path(::testing::TempDir()) / "command_line";
  const std::string example = std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/pendulum.xml";
  auto run = testing::RunMechflow("run " + example + " --interval=0.5 --t-end 2 --results=swing.csv --quiet --out " +
                                  out.string());
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.out, "");  // --quiet: nothing but errors
  const std::string csv = testing::ReadFile(out / "swing.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 6);  // header and t = 0, 0.5, ..., 2
  // a usage error: the wrong argument and the command's usage lines, not the whole help
  run = testing::RunMechflow("run " + example + " --rtol");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("mechflow run: --rtol needs a value"));
  EXPECT_THAT(run.err, HasSubstr("usage: mechflow run FILE"));
  EXPECT_THAT(run.err, ::testing::Not(HasSubstr("Commands:")));
  // settings the solver refuses name where they came from
  run = testing::RunMechflow("run " + example + " --rtol=-1 --out " + out.string());
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("the run's own solver settings (--t-end, --rtol, --atol; run()'s t_end, rtol, atol): rtol = -1"));
}

TEST(CommandLineTest, SetTakesExpressionsAndFiles) {
  const fs::path dir = fs::path(::testing::TempDir()) / "set_expressions";
  fs::create_directories(dir);
  std::ofstream(dir / "overrides.txt") << "# damping study\nbeta = 0.2   # a fifth of critical\n\nmass=500\n";
  const std::string example = std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/damping_ratio.xml";
  // f follows the mass from the file: f = 2 * sqrt(mass / 1000) Hz via an expression of identifiers
  const auto run = testing::RunMechflow("check " + example + " --set-file " + (dir / "overrides.txt").string() +
                                        " --set f=4*beta");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_THAT(run.out, HasSubstr("beta"));
  const Arguments a = ParseArguments({"run", "d.xml", "--set-file", (dir / "overrides.txt").string(), "--set=f=4*beta"});
  EXPECT_THAT(a.overrides, ElementsAre(std::pair<std::string, double>{"beta", 0.2},
                                       std::pair<std::string, double>{"mass", 500}));
  ASSERT_EQ(a.set_expressions.size(), 1u);
  EXPECT_EQ(a.set_expressions[0], (std::pair<std::string, std::string>{"f", "4*beta"}));
  // an expression over an unknown name is bad input naming the --set
  const auto bad = testing::RunMechflow("check " + example + " --set f=4*betta");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_THAT(bad.err, HasSubstr("--set f=4*betta"));
  EXPECT_THAT(bad.err, HasSubstr("betta"));
  std::ofstream(dir / "bad.txt") << "beta 0.2\n";
  EXPECT_THROW(ParseArguments({"run", "d.xml", "--set-file", (dir / "bad.txt").string()}), UsageError);
}

// A number on the command line is the whole text in decimal; a count is
// digits only. What std::stod would read as something else is refused,
// naming the option and the text.
TEST(CommandLineTest, NumbersAreTheWholeTextOrRefused) {
  for (const std::string text : {"1e-3", "-2.5", ".5", "7"}) EXPECT_NO_THROW(ParseNumber(text, "--t-end")) << text;
  for (const std::string text : {"1abc", "0x10", "inf", "-inf", "nan", "", " 1", "1 ", "1e400", "1,5"}) {
    try {
      ParseNumber(text, "--t-end");
      ADD_FAILURE() << "accepted '" << text << "'";
    } catch (const UsageError& e) {
      EXPECT_THAT(e.what(), HasSubstr("--t-end: '" + text + "'"));
    }
  }
  EXPECT_EQ(ParseCount("12", "--jobs", 1, 4096), 12);
  for (const std::string text : {"1e1", "2.0", "0x10", "-1", "0", "4097", "", "3 "})
    EXPECT_THROW(ParseCount(text, "--jobs", 1, 4096), UsageError) << text;
  // every numeric option goes through them
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"run", "d.xml", "--t-end", "1abc"}, {"run", "d.xml", "--rtol", "0x10"},
        {"run", "d.xml", "--interval=nan"}, {"sweep", "d.xml", "--vary", "k=1,2abc"},
        {"sweep", "d.xml", "--vary", "k=1:2:1e1"}, {"sweep", "d.xml", "--vary", "k=1", "--jobs", "1e1"},
        {"run", "d.xml", "--set", "k=inf"}, {"run", "d.xml", "--set=k=nan"}})
    EXPECT_THROW(ParseArguments(args), UsageError) << args[2] << " " << args.back();
}

// --set-file reads a regular file of bounded size: /dev/zero (endless) and a
// FIFO nobody writes to (blocks forever) are refused at once.
TEST(CommandLineTest, SetFileIsARegularFile) {
  const fs::path dir = fs::path(::testing::TempDir()) / "set_file_kinds";
  fs::create_directories(dir);
  const fs::path fifo = dir / "fifo";
  fs::remove(fifo);
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  for (const std::string& path : {std::string("/dev/zero"), fifo.string(), dir.string()}) {
    try {
      ParseArguments({"run", "d.xml", "--set-file", path});
      ADD_FAILURE() << "accepted " << path;
    } catch (const UsageError& e) {
      EXPECT_THAT(e.what(), HasSubstr("--set-file: file '" + path + "' is not a regular file")) << path;
    }
  }
  const auto run = testing::RunMechflow("check d.xml --set-file /dev/zero");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("a device"));
}

TEST(CommandLineTest, VerboseLogsEveryEventWithItsElement) {
  const fs::path out = fs::path(::testing::TempDir()) / "verbose";
  const auto run = testing::RunMechflow("run " + std::string(MECHFLOW_SOURCE_DIR) +
                                        "/diagrams/examples/elast_friction.xml --variant 'Simple spring' --verbose --out " +
                                        out.string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  // FR-2 with the stick spring: breakaway, then every reversal a stop and a breakaway, the last stop for good
  std::size_t events = 0;
  for (std::size_t at = run.out.find("event: t = "); at != std::string::npos; at = run.out.find("event: t = ", at + 1))
    ++events;
  EXPECT_EQ(events, 10u);
  EXPECT_THAT(run.out, HasSubstr("s: m.friction: breaks away: slip-"));
  EXPECT_THAT(run.out, HasSubstr("s: m.friction: slip- ends: sticks"));
  const auto quiet = testing::RunMechflow("run " + std::string(MECHFLOW_SOURCE_DIR) +
                                          "/diagrams/examples/elast_friction.xml --out " + out.string());
  EXPECT_THAT(quiet.out, ::testing::Not(HasSubstr("event: t = ")));
}

// check compiles every Lua chunk when loading and names the globals one
// reads that nothing defines, at the chunk's file:line.
TEST(CommandLineTest, CheckNamesGlobalsNothingDefines) {
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "check_globals";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "d.xml") << "<diagram name='d'>\n"
                                  "<identifiers><identifier name='Kp' value='2'/></identifiers>\n"
                                  "<blocks>\n"
                                  "<block type='lua' name='f' outputs='y'><![CDATA[\n"
                                  "function outputs(t) return kp * t + gian end\n"
                                  "]]></block>\n"
                                  "</blocks>\n"
                                  "<script>\n"
                                  "function step(sim) local phi = sim:get('f.y'); kp_gain = phi * Kpp end\n"
                                  "</script>\n"
                                  "<solver t_end='1'/></diagram>\n";
  const auto run = testing::RunMechflow("check " + (dir / "d.xml").string());
  EXPECT_EQ(run.exit_code, 0) << run.err;
  const std::string file = (dir / "d.xml").string();
  EXPECT_THAT(run.out, HasSubstr(file + ":9: warning: 'Kpp' is read as a global but is no identifier"));
  EXPECT_THAT(run.out, HasSubstr("did you mean 'Kp'"));
  EXPECT_THAT(run.out, HasSubstr(file + ":5: warning: 'gian' is read as a global"));
  EXPECT_THAT(run.out, ::testing::Not(HasSubstr("'kp_gain'")));  // assigned, not read
  EXPECT_THAT(run.out, HasSubstr(": ok (2 warnings)"));
}

// check and run agree on what a control script reads: an identifier is read
// by name (no warning, and the run sees it), a name nothing defines is nil
// (a warning, and the run fails where it is read).
TEST(CommandLineTest, CheckAndRunAgreeOnTheNamesAControlScriptReads) {
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "check_script_names";
  std::filesystem::create_directories(dir);
  const auto write = [&](const std::string& read) {
    std::ofstream(dir / "d.xml") << "<diagram name='d'>\n"
                                    "<identifiers><identifier name='Ts' value='0.25'/>"
                                    "<identifier name='u' value='0'/></identifiers>\n"
                                    "<blocks><block type='identifier' name='i' identifier='u'/></blocks>\n"
                                    "<script>\n"
                                    "function init(sim) sim:every(" + read + ", function(sim) sim:set('u', sim.t) end) end\n"
                                    "</script>\n"
                                    "<solver t_end='1'/><output interval='0.5'><log signal='i.y'/></output></diagram>\n";
  };
  const std::string file = (dir / "d.xml").string();
  write("Ts");
  const auto check = testing::RunMechflow("check " + file);
  EXPECT_EQ(check.exit_code, 0) << check.err;
  EXPECT_THAT(check.out, ::testing::Not(HasSubstr("warning")));
  const auto run = testing::RunMechflow("run " + file + " --out " + (dir / "out").string());
  EXPECT_EQ(run.exit_code, 0) << run.err;

  write("Tss");
  const auto misspelt = testing::RunMechflow("check " + file);
  EXPECT_THAT(misspelt.out, HasSubstr(file + ":5: warning: 'Tss' is read as a global but is no identifier"));
  EXPECT_THAT(misspelt.out, HasSubstr(": ok (1 warning)"));
  const auto fails = testing::RunMechflow("run " + file + " --out " + (dir / "out").string());
  EXPECT_EQ(fails.exit_code, 1);
  EXPECT_THAT(fails.err, HasSubstr("number expected, got nil"));
}

// --verbose names what every block's event meant, not only mechanisms'.
TEST(CommandLineTest, VerboseNamesBlockEvents) {
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "verbose_blocks";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "d.xml") << "<diagram name='d'><identifiers><identifier name='A' value='1'/></identifiers>"
                                  "<blocks><block type='sine' name='s' amplitude='A'/><block type='abs' name='a'/>"
                                  "<block type='lookup' name='f' points='0 0; 0.5 1; 1 0'/></blocks><connections>"
                                  "<connect from='s.y' to='a.u'/><connect from='s.y' to='f.u'/></connections>"
                                  "<solver t_end='1'/><output interval='0.1'><log signal='a.y'/><log signal='f.y'/>"
                                  "</output></diagram>";
  const auto run = testing::RunMechflow("run " + (dir / "d.xml").string() + " --verbose --out " + (dir / "out").string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_THAT(run.out, HasSubstr("s: a: u falls past 0\n"));  // sin(2 pi t) at t = 0.5
  EXPECT_THAT(run.out, HasSubstr("s: f: u rises past a breakpoint\n"));
  EXPECT_THAT(run.out, ::testing::Not(HasSubstr("zero crossing")));
  // a sweep writes each run's log beside its results
  const auto sweep = testing::RunMechflow("sweep " + (dir / "d.xml").string() + " --vary A=1,2 --verbose --out " +
                                          (dir / "sweep").string());
  ASSERT_EQ(sweep.exit_code, 0) << sweep.err;
  EXPECT_THAT(testing::ReadFile(dir / "sweep" / "d.run2.A=2.events.txt"), HasSubstr("s: a: u falls past 0\n"));
}

// --library DIR reaches the read of every command that reads a diagram (each
// passes its options on its own way): a subsystem file found only there is
// found. psd reads a results file and takes no --library.
TEST(CommandLineTest, EveryCommandReadingADiagramLooksInTheLibrary) {
  const fs::path dir = fs::path(::testing::TempDir()) / "library_option";
  fs::create_directories(dir / "d");
  fs::create_directories(dir / "lib");
  std::ofstream(dir / "lib" / "sub.xml") << "<subsystem name=\"sub\"><output name=\"y\"/></subsystem>\n";
  const std::string diagram = (dir / "d" / "top.xml").string();
  std::ofstream(diagram) << "<diagram><blocks><block type=\"subsystem\" name=\"s\" src=\"sub.xml\"/></blocks>"
                            "<solver t_end=\"0.1\"/></diagram>\n";
  const std::string out = " --out " + (dir / "out").string();
  const auto missing = testing::RunMechflow("run " + diagram + out);
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_THAT(missing.err, HasSubstr("file 'sub.xml' not found"));
  for (const std::string command : {"run", "check", "graph", "modes", "sweep --vary k=1,2",
                                    "force-analysis --element f --amplitude 0.1 --frequency 1"}) {
    const auto found = testing::RunMechflow(command + " " + diagram + " --library " + (dir / "lib").string() + out);
    EXPECT_THAT(found.err, ::testing::Not(HasSubstr("not found"))) << command;
    EXPECT_THAT(found.err, ::testing::Not(HasSubstr("unknown option"))) << command;
  }
  EXPECT_THAT(ParseArguments({"check", "d.xml", "--library", "a", "--library=b"}).library, ElementsAre("a", "b"));
  EXPECT_THROW(ParseArguments({"psd", "r.csv", "--library", "a"}), UsageError);
}

}  // namespace
}  // namespace mechflow::cli
