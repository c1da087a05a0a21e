// Control scripts: init/step/finish, sim:every at exact times, sim:get,
// sim:set with re-evaluation and re-initialisation, sim:stop, errors and
// limits. Each diagram is small enough that its answer is known in closed form.

#include "scripting/control_script.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <cmath>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/test_util.h"

namespace mechflow::scripting {
namespace {

using mechflow::testing::InputErrorOf;
using mechflow::testing::LoadXml;
using mechflow::testing::RunXml;
using ::testing::HasSubstr;

// x' = u where u is the identifier `u` (an identifier block), y = b t with b =
// 2 a read by an expression block; `script` is the <script> content, `extra`
// more elements inside <diagram>.
std::string Diagram(const std::string& script, const std::string& solver = R"(<solver t_end="1"/>)",
                    const std::string& extra = "") {
  return R"(<diagram name="d">
  <identifiers>
    <identifier name="u" value="0"/>
    <identifier name="a" value="1"/>
    <identifier name="b" value="2*a"/>
    <identifier name="k" value="3"/>
  </identifiers>
  <blocks>
    <block type="identifier" name="input" identifier="u"/>
    <block type="integrator" name="x"/>
    <block type="expression" name="y" inputs="" expr="b*t"/>
    <block type="gain" name="g" k="k"/>
  </blocks>
  <connections>
    <connect from="input.y" to="x.u"/>
    <connect from="x.y" to="g.u"/>
  </connections>
  <script>)" + script + R"(</script>
  )" + solver + extra + R"(
  <output interval="0.1">
    <log signal="x.y" label="x"/>
    <log signal="y.y" label="y"/>
    <log signal="input.y" label="u"/>
  </output>
</diagram>)";
}

TEST(ControlScriptTest, EveryRunsAtExactTimesAndTheIntegratorStopsThere) {
  // u jumps to 1 at the sample 0.35: x = t - 0.35 afterwards, exactly so only
  // if the integrator stopped at 0.35 and restarted with the new input
  auto run = RunXml(Diagram(R"(
    function init(sim)
      sim:every(0.35, function(sim)
        if sim.t > 0 then sim:set("u", 1) end
      end)
    end)"));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto t = run.Column("time"), x = run.Column("x"), u = run.Column("u");
  for (std::size_t i = 0; i < t.size(); ++i) {
    EXPECT_NEAR(x[i], std::max(0.0, t[i] - 0.35), 1e-9) << "t = " << t[i];
    EXPECT_EQ(u[i], t[i] >= 0.35 ? 1.0 : 0.0) << "t = " << t[i];
  }
  EXPECT_EQ(run.sim->stats().reinits, 2);  // at the samples 0.35 and 0.7
  ASSERT_NE(run.loaded.control, nullptr);
  ASSERT_EQ(run.loaded.control->changes().size(), 2u);
  EXPECT_EQ(run.loaded.control->changes()[0].time, 0.35);
  EXPECT_EQ(run.loaded.control->changes()[1].time, 0.7);
}

TEST(ControlScriptTest, StepRunsBeforeEachRowAndDerivedIdentifiersFollow) {
  // a = 1 + t at every output time: b = 2 a, and y = b t follows at once
  auto run = RunXml(Diagram(R"(
    function init(sim) sim:set("a", 1 + sim.t) end
    function step(sim) sim:set("a", 1 + sim.t) end)"));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto t = run.Column("time"), y = run.Column("y");
  ASSERT_EQ(t.size(), 11u);
  for (std::size_t i = 0; i < t.size(); ++i) EXPECT_NEAR(y[i], 2 * (1 + t[i]) * t[i], 1e-12) << "t = " << t[i];
  EXPECT_EQ(run.loaded.control->callbacks(), 11);
}

TEST(ControlScriptTest, GetReadsSignalsIdentifiersAndUniquePortNames) {
  // '<' needs CDATA (or &lt;) in XML
  auto run = RunXml(Diagram(R"(<![CDATA[
    function init(sim) sim:set("u", 2) end
    function finish(sim)
      -- x = 2 t at t = 1; g.y = k x; identifiers by name
      assert(math.abs(sim:get("x.y") - 2) < 1e-9, "x.y")
      assert(math.abs(sim:get("g.y") - 6) < 1e-8, "g.y")
      assert(sim:get("b") == 2 and sim:get("K") == 3, "identifiers")
      sim:set("a", 5)  -- finish may still change identifiers
      assert(sim:get("b") == 10, "b follows a")
    end]]>)"));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;

  auto ambiguous = RunXml(Diagram(R"(function init(sim) sim:get("y") end)"));
  ASSERT_FALSE(ambiguous.outcome.ok);
  EXPECT_THAT(ambiguous.outcome.failure, HasSubstr("'y' is an output of several blocks"));
  auto unknown = RunXml(Diagram(R"(function init(sim) sim:get("x.yy") end)"));
  ASSERT_FALSE(unknown.outcome.ok);
  EXPECT_THAT(unknown.outcome.failure, HasSubstr("test.xml:"));
  EXPECT_THAT(unknown.outcome.failure, HasSubstr("init(sim)"));
}

// An identifier whose name is an instance path (a subsystem's parameter,
// d[1].mu) is got and set by that name, dots and all; another dotted name is
// still a signal.
TEST(ControlScriptTest, GetAndSetTakeIdentifiersNamedByPaths) {
  diagrams::DiagramDescription description = diagrams::ReadDiagramText(Diagram(R"(<![CDATA[
    function init(sim)
      assert(sim:get("d[1].mu") == 0.25, "loaded: " .. tostring(sim:get("d[1].mu")))
      sim:set("D[1].MU", 0.5)  -- any case, as other identifiers
      assert(sim:get("d[1].mu") == 0.5, "after sim:set: " .. tostring(sim:get("d[1].mu")))
      assert(sim:get("x.y") == 0, "x.y is a signal")
    end]]>)"), "test.xml");
  description.identifiers.push_back({"d[1].mu", "0.25", "", "", {}});
  auto run = mechflow::testing::RunDescription(std::move(description));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
}

// A part's sensor has a dotted name (s[1].z, an output of mechanism m):
// sim:get takes it alone, as other sensor names, or as m.s[1].z.
TEST(ControlScriptTest, GetTakesTheDottedSensorNameOfAPart) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(::testing::TempDir()) / "control_script_parts";
  fs::create_directories(dir);
  std::ofstream(dir / "slider.xml") << R"(<part name="slider">
  <attach name="base"/>
  <body name="Box" mass="1" inertia="1 1 1"/>
  <joint name="j" type="translational" body1="base" body2="Box" axis="0 0 1"/>
  <sensor name="z" kind="coordinate" dof="j"/>
</part>
)";
  std::ofstream(dir / "parts.xml") << R"(<diagram name="parts">
  <mechanism name="m"><include part="slider.xml" name="s" count="2" attach="base=Base0"/></mechanism>
  <script><![CDATA[
    function finish(sim)
      local z = sim:get("m.s[1].z")
      assert(z < -0.04, "fallen: " .. tostring(z))
      assert(sim:get("s[1].z") == z, "by the sensor name alone")
    end]]></script>
  <solver t_end="0.1"/>
</diagram>
)";
  const auto run = mechflow::testing::RunDescription(diagrams::ReadDiagramFile((dir / "parts.xml").string()));
  EXPECT_TRUE(run.outcome.ok) << run.outcome.failure;
}

TEST(ControlScriptTest, AFixedIdentifierCannotChangeAndTheRunKeepsItsResults) {
  auto run = RunXml(Diagram(R"(
    function step(sim) if sim.t >= 0.5 then sim:set("k", 4) end end)"));
  ASSERT_FALSE(run.outcome.ok);
  EXPECT_THAT(run.outcome.failure, HasSubstr("identifier 'k' cannot change during a run"));
  EXPECT_THAT(run.outcome.failure, HasSubstr("block 'g'"));
  EXPECT_THAT(run.outcome.failure, HasSubstr("step(sim) at t = 0.5"));
  EXPECT_EQ(run.sim->results().num_rows(), 5);  // t = 0 .. 0.4
  EXPECT_EQ(run.loaded.identifiers->Value("k"), 3.0);  // refused: unchanged

  auto derived = RunXml(Diagram(R"(function init(sim) sim:set("b", 1) end)"));
  ASSERT_FALSE(derived.outcome.ok);
  EXPECT_THAT(derived.outcome.failure, HasSubstr("identifier 'b' is defined by an expression"));
  auto unknown = RunXml(Diagram(R"(function init(sim) sim:set("uu", 1) end)"));
  ASSERT_FALSE(unknown.outcome.ok);
  EXPECT_THAT(unknown.outcome.failure, HasSubstr("no identifier named 'uu' (did you mean 'u'?)"));
}

TEST(ControlScriptTest, StopEndsTheRunSuccessfullyWithARowAtThatInstant) {
  auto run = RunXml(Diagram(R"(
    function init(sim)
      sim:set("u", 1)
      sim:every(0.25, function(sim) if sim.t >= 0.5 then sim:stop("far enough") end end)
    end)"));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  EXPECT_TRUE(run.outcome.stopped);
  EXPECT_EQ(run.outcome.stop_reason, "far enough");
  EXPECT_EQ(run.outcome.t_reached, 0.5);
  const auto t = run.Column("time"), x = run.Column("x");
  EXPECT_EQ(t.back(), 0.5);
  EXPECT_NEAR(x.back(), 0.5, 1e-9);
}

TEST(ControlScriptTest, RuntimeErrorNamesCallbackLineAndTracebackAndKeepsResults) {
  const std::string xml = Diagram(R"(
    function step(sim)
      if sim.t > 0.25 then
        local z = nil + 1
      end
    end)");
  auto run = RunXml(xml);
  ASSERT_FALSE(run.outcome.ok);
  const int line = 1 + static_cast<int>(std::count(xml.begin(), xml.begin() + xml.find("nil + 1"), '\n'));
  EXPECT_THAT(run.outcome.failure, HasSubstr("step(sim) at t = 0.3 s failed: test.xml:" + std::to_string(line) +
                                             ": attempt to perform arithmetic on a nil value"));
  EXPECT_THAT(run.outcome.failure, HasSubstr("stack traceback"));
  EXPECT_EQ(run.sim->results().num_rows(), 3);  // 0, 0.1, 0.2
  EXPECT_NEAR(run.outcome.t_reached, 0.3, 1e-12);
}

TEST(ControlScriptTest, SyntaxErrorsAndBadCallbacksAreBadInputWithTheLine) {
  const std::string xml = Diagram("\n    function step(sim) return ) end");
  const int line = 1 + static_cast<int>(std::count(xml.begin(), xml.begin() + xml.find("return )"), '\n'));
  EXPECT_THAT(InputErrorOf([&] { LoadXml(xml); }), HasSubstr("test.xml:" + std::to_string(line) + ": unexpected symbol"));
  // inside CDATA (a script with < or &) the lines are the file's too
  for (const std::string code : {"<![CDATA[\n    function step(sim) return ) end]]>",
                                 "\n  <![CDATA[\n\n    function step(sim) return ) end]]>",
                                 "<![CDATA[function step(sim) return ) end]]>"}) {
    const std::string cdata = Diagram(code);
    const int at = 1 + static_cast<int>(std::count(cdata.begin(), cdata.begin() + cdata.find("return )"), '\n'));
    EXPECT_THAT(InputErrorOf([&] { LoadXml(cdata); }), HasSubstr("test.xml:" + std::to_string(at) + ": unexpected symbol"))
        << code;
  }
  EXPECT_THAT(InputErrorOf([&] { LoadXml(Diagram("step = 3")); }), HasSubstr("'step' is a number"));
  EXPECT_THAT(InputErrorOf([&] { LoadXml(Diagram("")); }), HasSubstr("<script> is empty"));
}

TEST(ControlScriptTest, AnEndlessLoopInStepEndsTheRunWithinASecond) {
  const auto start = std::chrono::steady_clock::now();
  auto run = RunXml(Diagram(R"(function step(sim) if sim.t > 0.45 then while true do end end end)"));
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_FALSE(run.outcome.ok);
  EXPECT_THAT(run.outcome.failure, HasSubstr("instruction limit"));
  EXPECT_LT(wall, 1.0);
  EXPECT_EQ(run.sim->results().num_rows(), 5);
}

TEST(ControlScriptTest, TheSandboxHoldsUnlessTheUserOptsIn) {
  const std::string xml = Diagram(R"(function init(sim) sim:set("a", os.time() > 0 and 2 or 3) end)");
  auto sandboxed = RunXml(xml);
  ASSERT_FALSE(sandboxed.outcome.ok);
  EXPECT_THAT(sandboxed.outcome.failure, HasSubstr("global 'os'"));
  diagrams::LoadOptions unsafe;
  unsafe.unsafe_lua = true;
  auto opted_in = RunXml(xml, unsafe);
  EXPECT_TRUE(opted_in.outcome.ok) << opted_in.outcome.failure;
}

TEST(ControlScriptTest, EachRunStartsFromTheLoadedValues) {
  auto run = RunXml(Diagram(R"(
    function init(sim)
      assert(sim:get("u") == 0 and sim:get("b") == 2, "loaded values")
      sim:every(0.5, function(sim) sim:set("u", sim:get("u") + 1); sim:set("a", 7) end, 0.5)
    end)"));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const std::vector<double> first = run.Column("x");
  run.outcome = run.sim->Run();
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  EXPECT_EQ(run.Column("x"), first);
  EXPECT_NEAR(first.back(), 0.5, 1e-9);  // u = 1 from 0.5 on
}

TEST(ControlScriptTest, LogWritesTheTimeAndValuesToStderr) {
  ::testing::internal::CaptureStderr();
  auto run = RunXml(Diagram(R"(function finish(sim) sim:log("done", 42, true) end)"));
  const std::string err = ::testing::internal::GetCapturedStderr();
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  EXPECT_EQ(err, "t = 1.0: done\t42\ttrue\n");
}

// A timer due at t_end runs before the last row (3 * 0.1 passes 0.3 by a rounding).
TEST(ControlScriptTest, ATimerAtTheEndRunsBeforeTheLastRow) {
  auto run = RunXml(Diagram(R"(function init(sim) sim:every(0.1, function(sim) sim:set("u", sim.t) end) end)",
                            R"(<solver t_end="0.3"/>)"));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const std::vector<double> u = run.Column("u");
  ASSERT_EQ(u.size(), 4u);
  EXPECT_NEAR(u.back(), 0.3, 1e-12);
}

TEST(ControlScriptTest, EveryChecksItsArguments) {
  auto run = RunXml(Diagram(R"(function init(sim) sim:every(0, function() end) end)"));
  ASSERT_FALSE(run.outcome.ok);
  EXPECT_THAT(run.outcome.failure, HasSubstr("sim:every: the period must be > 0"));
  auto no_function = RunXml(Diagram(R"(function init(sim) sim:every(1, 2) end)"));
  ASSERT_FALSE(no_function.outcome.ok);
  EXPECT_THAT(no_function.outcome.failure, HasSubstr("function expected"));
}

TEST(ControlScriptTest, ReportsSeeOnlyTheSolutionTheRunKept) {
  // x' = u from 0: u = 1 until the script sets -1 at t = 0.5, so the peak of x
  // is 0.5 at 0.5. The solver's large steps on x' = 1 take it past 0.5 before
  // the row there; what it computed beyond, with u = 1, must not count.
  auto run = RunXml(R"(<diagram name="d">
  <identifiers><identifier name="u" value="1"/></identifiers>
  <blocks>
    <block type="identifier" name="input" identifier="u"/>
    <block type="integrator" name="x"/>
  </blocks>
  <connections><connect from="input.y" to="x.u"/></connections>
  <script>function step(sim) if sim.t == 0.5 then sim:set("u", -1) end end</script>
  <solver t_end="1"/>
  <output interval="0.1">
    <log signal="x.y" label="x"/>
    <report peak="x.y" label="highest"/>
  </output>
</diagram>)");
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto& figures = run.sim->results().figures();
  ASSERT_EQ(figures.size(), 1u);
  EXPECT_NEAR(figures[0].value, 0.5, 1e-9);
  EXPECT_NEAR(figures[0].time, 0.5, 1e-9);
  EXPECT_NEAR(run.Column("x").back(), 0.0, 1e-9);
}

TEST(ControlScriptTest, ASetThatBreaksTheModelFailsTheCallback) {
  // y = b t with b = 2 a: an expression block that fails for a > 5
  std::string xml = Diagram(R"(function step(sim) if sim.t >= 0.5 then sim:set("a", 6) end end)");
  const std::string expr = "expr=\"b*t\"";
  xml.replace(xml.find(expr), expr.size(), "expr=\"a &gt; 5 and error('too big') or b*t\"");
  auto run = RunXml(xml);
  ASSERT_FALSE(run.outcome.ok);
  EXPECT_THAT(run.outcome.failure, HasSubstr("sim:set: the model fails with a = 6"));
  EXPECT_THAT(run.outcome.failure, HasSubstr("too big"));
  EXPECT_EQ(run.sim->results().num_rows(), 5);
}

TEST(ControlScriptTest, IdentifiersAreReadByNameWithTheirCurrentValues) {
  // the period of sim:every is an identifier read by name (any case); after a
  // set of u, and of a (b = 2 a follows), the script sees the new values
  std::string xml = Diagram(R"(<![CDATA[
    seen_at_load = B
    function init(sim)
      assert(u == 0 and b == 2, "the loaded values: " .. tostring(u) .. ", " .. tostring(b))
      samples = 0
      sim:every(Ts, function(sim) samples = samples + 1 end)
      sim:set("u", 4)
      assert(U == 4 and ts == 0.25, "u after sim:set: " .. tostring(U))
      sim:set("a", 5)
      assert(b == 10 and A == 5, "b follows a: " .. tostring(b))
    end
    function finish(sim)
      assert(seen_at_load == 2, "b at load")
      assert(samples == 5, "samples: " .. tostring(samples))  -- 0, 0.25, ..., 1
    end]]>)");
  xml.replace(xml.find("<identifier name=\"k\""), 0, "<identifier name=\"Ts\" value=\"0.25\"/>");
  auto run = RunXml(xml);
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  EXPECT_NEAR(run.Column("x").back(), 4.0, 1e-9);  // x' = u = 4
  // a second run starts from the loaded values, in the script too
  run.outcome = run.sim->Run();
  EXPECT_TRUE(run.outcome.ok) << run.outcome.failure;
}

TEST(ControlScriptTest, AnIdentifierCannotBeAssignedButALocalMayHideIt) {
  const std::string xml = Diagram("\n    function step(sim) K = 4 end");
  const int line = 1 + static_cast<int>(std::count(xml.begin(), xml.begin() + xml.find("K = 4"), '\n'));
  const std::string error = InputErrorOf([&] { LoadXml(xml); });
  EXPECT_THAT(error, HasSubstr("test.xml:" + std::to_string(line) + ": attempt to assign to const variable 'k'"));
  EXPECT_THAT(error, HasSubstr("change it with sim:set('k', value)"));
  // a local of the name, a field and a table key are not the identifier
  auto run = RunXml(Diagram(R"(
    local k = 7
    function init(sim)
      local t = { a = 1 }
      t.b = 2
      assert(k == 7 and t.a == 1 and t.b == 2 and b == 2)
      k = 8
    end)"));
  EXPECT_TRUE(run.outcome.ok) << run.outcome.failure;
}

}  // namespace
}  // namespace mechflow::scripting
