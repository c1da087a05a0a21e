// The mechflow command, run as a user would: exit codes, messages, files.

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/cli/mechflow_command.h"

namespace mechflow::cli {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;
using ::testing::StartsWith;
namespace fs = std::filesystem;

using Outcome = mechflow::testing::CommandOutcome;
using mechflow::testing::ReadFile;

Outcome Mechflow(const std::string& args) { return mechflow::testing::RunMechflow(args); }

std::string Example(const std::string& name) {
  return std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/" + name;
}

fs::path FreshDir(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / name;
  fs::remove_all(dir);
  return dir;
}

fs::path WriteDiagram(const std::string& name, const std::string& xml) {
  const fs::path path = fs::path(::testing::TempDir()) / name;
  std::ofstream(path) << xml;
  return path;
}

int CountLines(const std::string& text) { return static_cast<int>(std::count(text.begin(), text.end(), '\n')); }

TEST(CliTest, Help) {
  const Outcome general = Mechflow("--help");
  EXPECT_EQ(general.exit_code, 0);
  EXPECT_THAT(general.out, HasSubstr("Commands:"));
  const Outcome run_help = Mechflow("help run");
  EXPECT_THAT(run_help.out, StartsWith("usage: mechflow run FILE"));
  EXPECT_EQ(Mechflow("run --help").out, run_help.out);
  EXPECT_THAT(Mechflow("check --help").out, StartsWith("usage: mechflow check FILE"));
  const Outcome bad = Mechflow("rnu x.xml");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_THAT(bad.err, HasSubstr("unknown command 'rnu' (did you mean 'run'?)"));
  EXPECT_EQ(Mechflow("run").exit_code, 2);
  EXPECT_THAT(Mechflow("run x.xml --t-end abc").err, HasSubstr("--t-end: 'abc' is not a number"));
}

TEST(CliTest, CheckAndGraphEveryExample) {
  for (const auto& entry : fs::directory_iterator(Example(""))) {
    if (entry.path().extension() != ".xml") continue;
    const std::string name = entry.path().filename().string();
    const Outcome check = Mechflow("check " + Example(name));
    EXPECT_EQ(check.exit_code, 0) << name << check.err;
    EXPECT_THAT(check.out, HasSubstr("evaluation order (output ports):"));
    EXPECT_THAT(check.out, HasSubstr("continuous states:"));
    // no load warning (units, contacts that start beyond their bound): an example shows a sound model
    EXPECT_THAT(check.out, Not(HasSubstr("warning"))) << name;
    const Outcome graph = Mechflow("graph " + Example(name));
    EXPECT_EQ(graph.exit_code, 0) << name;
    EXPECT_THAT(graph.out, StartsWith("digraph"));
    if (ReadFile(entry.path()).find("<connect") != std::string::npos) {
      EXPECT_THAT(graph.out, HasSubstr(" -> "));
    }
  }
}

// An algebraic loop is listed by check with its hops and unknowns, and run
// reports how its Newton iteration went.
TEST(CliTest, AlgebraicLoopIsListedAndReported) {
  const Outcome check = Mechflow("check " + Example("cart_pendulum_friction.xml"));
  ASSERT_EQ(check.exit_code, 0) << check.err;
  EXPECT_THAT(check.out, HasSubstr("algebraic loop through m.N:"));
  EXPECT_THAT(check.out, HasSubstr("coulomb.F -> m.Ffr (feeds m.N directly) at "));
  EXPECT_THAT(check.out, HasSubstr("through m.N, solved by Newton on m.N (1 unknown)"));
  const Outcome run = Mechflow("run " + Example("cart_pendulum_friction.xml") + " --out " +
                               FreshDir("mechflow_loop").string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_THAT(run.out, HasSubstr("algebraic loop through m.N: "));
  EXPECT_THAT(run.out, HasSubstr("Newton steps per solve"));
}

// y = y + 1 has no solution: the run fails with exit 1 naming the loop.
TEST(CliTest, UnsolvableLoopFailsNamingIt) {
  const fs::path xml = WriteDiagram("unsolvable_loop.xml", R"xml(<diagram>
  <blocks>
    <block type="gain" name="a" k="1"/>
    <block type="sum" name="s"/>
    <block type="constant" name="c" value="1"/>
  </blocks>
  <connections>
    <connect from="a.y" to="s.u1"/>
    <connect from="c.y" to="s.u2"/>
    <connect from="s.y" to="a.u"/>
  </connections>
  <solver t_end="1"/>
</diagram>)xml");
  const Outcome run = Mechflow("run " + xml.string() + " --out " + FreshDir("mechflow_bad_loop").string());
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_THAT(run.err, HasSubstr("algebraic loop through"));
  EXPECT_THAT(run.err, HasSubstr("no unique solution"));
  EXPECT_THAT(run.err, HasSubstr("unsolvable_loop.xml:8"));
}

TEST(CliTest, RunWritesCsvAndPlot) {
  const fs::path out = FreshDir("mechflow_run");
  const Outcome run = Mechflow("run " + Example("damped_oscillator_blocks.xml") + " --out " + out.string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_THAT(run.out, HasSubstr("steps"));
  EXPECT_THAT(run.out, HasSubstr("RHS evaluations"));
  const std::string csv = ReadFile(out / "damped_oscillator_blocks.csv");
  EXPECT_THAT(csv, StartsWith("time,x,v\n"));
  EXPECT_EQ(CountLines(csv), 1002);  // header + t = 0, 0.01, ..., 10
  if (std::system("command -v gnuplot >/dev/null 2>&1") == 0) {
    EXPECT_TRUE(fs::exists(out / "damped_oscillator_blocks.png"));
    EXPECT_TRUE(fs::exists(out / "damped_oscillator_blocks.png.gp"));
  } else {
    EXPECT_THAT(run.err, HasSubstr("gnuplot not found"));
  }
}

TEST(CliTest, SetAndTEndChangeTheRun) {
  const fs::path a = FreshDir("mechflow_set_a"), b = FreshDir("mechflow_set_b");
  ASSERT_EQ(Mechflow("run " + Example("damped_oscillator_blocks.xml") + " --out " + a.string()).exit_code, 0);
  ASSERT_EQ(Mechflow("run " + Example("damped_oscillator_blocks.xml") + " --set beta=0.2 --t-end 1 --out " +
                     b.string()).exit_code,
            0);
  const std::string csv_a = ReadFile(a / "damped_oscillator_blocks.csv");
  const std::string csv_b = ReadFile(b / "damped_oscillator_blocks.csv");
  EXPECT_EQ(CountLines(csv_b), 1 + 101);  // t_end 1 keeps the output interval of the diagram (0.01)
  // same start, different damping: the rows differ after the first
  EXPECT_EQ(csv_a.substr(0, csv_a.find('\n', 10)), csv_b.substr(0, csv_b.find('\n', 10)));
  EXPECT_NE(csv_a.substr(0, 2000), csv_b.substr(0, 2000));
  const Outcome derived = Mechflow("run " + Example("damped_oscillator_blocks.xml") + " --set c=1");
  EXPECT_EQ(derived.exit_code, 2);
  EXPECT_THAT(derived.err, HasSubstr("--set c: identifier 'c' is defined by an expression"));
}

TEST(CliTest, BadDiagramExitsWithOneMessage) {
  const fs::path path = WriteDiagram("mechflow_bad.xml", "<diagram>\n<blocks>\n<block type='gain' name='g'/>\n"
                                                         "</blocks>\n</diagram>\n");
  const Outcome run = Mechflow("run " + path.string());
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("mechflow_bad.xml:3: block 'g' (gain) needs the parameter 'k'"));
  EXPECT_EQ(CountLines(run.err), 1);
  EXPECT_EQ(run.out, "");
  EXPECT_EQ(Mechflow("check " + path.string()).exit_code, 2);
  EXPECT_EQ(Mechflow("check /nonexistent/d.xml").exit_code, 2);
}

// A run that fails part-way keeps and writes what it computed.
TEST(CliTest, FailedRunWritesResultsUpToTheFailure) {
  const fs::path lua_error = WriteDiagram("mechflow_fail.xml", R"xml(<diagram name="fail">
  <blocks>
    <block type="clock" name="clk"/>
    <block type="expression" name="f" inputs="u" expr="u &lt; 0.5 and u or error('boom')"/>
    <block type="integrator" name="x"/>
  </blocks>
  <connections>
    <connect from="clk.y" to="f.u"/>
    <connect from="f.y" to="x.u"/>
  </connections>
  <solver t_end="2"/>
  <output interval="0.01"><log signal="x.y" label="x"/></output>
</diagram>)xml");
  const fs::path out = FreshDir("mechflow_fail");
  const Outcome run = Mechflow("run " + lua_error.string() + " --out " + out.string());
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_THAT(run.err, HasSubstr("simulation failed at t = 0.5 s"));
  EXPECT_THAT(run.err, HasSubstr("block 'f':1: boom"));
  const std::string csv = ReadFile(out / "fail.csv");
  EXPECT_GE(CountLines(csv), 50);  // rows up to t = 0.5 only
  EXPECT_LE(CountLines(csv), 53);

  // x' = x^2, x(0) = 1 has x = 1 / (1 - t): it blows up at t = 1
  const fs::path blow_up = WriteDiagram("mechflow_blowup.xml", R"xml(<diagram name="blowup">
  <blocks>
    <block type="integrator" name="x" initial="1"/>
    <block type="product" name="sq"/>
  </blocks>
  <connections>
    <connect from="x.y" to="sq.u1"/>
    <connect from="x.y" to="sq.u2"/>
    <connect from="sq.y" to="x.u"/>
  </connections>
  <solver t_end="2" max_steps="20000"/>
  <output interval="0.01"><log signal="x.y" label="x"/></output>
</diagram>)xml");
  const Outcome blown = Mechflow("run " + blow_up.string() + " --out " + out.string());
  EXPECT_EQ(blown.exit_code, 1);
  EXPECT_THAT(blown.err, HasSubstr("simulation failed at t = "));
  const std::string csv2 = ReadFile(out / "blowup.csv");
  EXPECT_GE(CountLines(csv2), 100);  // rows up to t = 0.99 at least
  EXPECT_LE(CountLines(csv2), 103);
}

TEST(CliTest, ControlScriptChangesArePrintedAndWritten) {
  const fs::path out = FreshDir("mechflow_molecule");
  const Outcome run = Mechflow("run " + Example("molecule.xml") + " --out " + out.string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_THAT(run.out, HasSubstr("control script: 201 callbacks, 201 identifier changes"));
  EXPECT_THAT(run.out, HasSubstr("mdeg: 201 times, first 3.1 at t = 0 s"));
  const std::string changes = ReadFile(out / "molecule.changes.csv");
  EXPECT_THAT(changes, StartsWith("time,identifier,value\n0,mdeg,3.1"));
  EXPECT_EQ(CountLines(changes), 202);
}

TEST(CliTest, ControlScriptErrorsStopsAndTheSandboxFlag) {
  const auto diagram = [](const std::string& name, const std::string& script) {
    return WriteDiagram(name + ".xml", R"xml(<diagram name=")xml" + name + R"xml(">
  <blocks><block type="clock" name="clk"/></blocks>
  <script>
    function step(sim)
      )xml" + script + R"xml(
    end
  </script>
  <solver t_end="1"/>
  <output interval="0.1"><log signal="clk.y" label="t"/></output>
</diagram>)xml");
  };
  const fs::path out = FreshDir("mechflow_scripts");
  // a run-time error: exit 1, callback, time, file:line and traceback; rows kept
  const Outcome failed =
      Mechflow("run " + diagram("script_error", "if sim.t > 0.45 then error('no') end").string() + " --out " +
               out.string());
  EXPECT_EQ(failed.exit_code, 1);
  EXPECT_THAT(failed.err, HasSubstr("step(sim) at t = 0.5 s failed: "));
  EXPECT_THAT(failed.err, HasSubstr("script_error.xml:5: no"));
  EXPECT_THAT(failed.err, HasSubstr("stack traceback"));
  EXPECT_EQ(CountLines(ReadFile(out / "script_error.csv")), 6);  // header and t = 0 .. 0.4

  // a stop is a finished run
  const Outcome stopped =
      Mechflow("run " + diagram("script_stop", "if sim.t >= 0.3 then sim:stop('enough') end").string() + " --out " +
               out.string());
  EXPECT_EQ(stopped.exit_code, 0) << stopped.err;
  EXPECT_THAT(stopped.out, HasSubstr("stopped by the control script at t = 0.3 s: enough"));

  // os exists only with --unsafe-lua
  const fs::path uses_os = diagram("script_os", "sim:log(os.getenv('HOME') ~= nil)");
  const Outcome sandboxed = Mechflow("run " + uses_os.string() + " --out " + out.string());
  EXPECT_EQ(sandboxed.exit_code, 1);
  EXPECT_THAT(sandboxed.err, HasSubstr("global 'os'"));
  EXPECT_EQ(Mechflow("run " + uses_os.string() + " --unsafe-lua --out " + out.string()).exit_code, 0);

  // a syntax error is bad input, at the script's line in the diagram
  const Outcome syntax = Mechflow("check " + diagram("script_syntax", "local = 1").string());
  EXPECT_EQ(syntax.exit_code, 2);
  EXPECT_THAT(syntax.err, HasSubstr("script_syntax.xml:5:"));
}

}  // namespace
}  // namespace mechflow::cli
