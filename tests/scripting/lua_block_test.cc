// The "lua" block (scripting/lua_block.h), loaded from inline XML and run by
// blocks::Simulator: states and derivatives against closed forms, ports with
// widths and declared feedthrough, an algebraic loop through Lua, identifiers
// changed during a run, and the messages of bad code and bad values.

#include "scripting/lua_block.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "scripting/identifier_bindings.h"
#include "tests/test_util.h"

namespace mechflow::scripting::lua_block_test {  // names of its own: the files of its folder are compiled together
namespace {

using mechflow::testing::InputErrorOf;
using mechflow::testing::LoadXml;
using mechflow::testing::RunXml;
using ::testing::HasSubstr;

// A diagram around `blocks` (and `connections`, `logs`), run to t_end.
std::string Diagram(const std::string& blocks, const std::string& connections, const std::string& logs,
                    double t_end = 1.0) {
  return "<diagram>\n"
         "  <identifiers>\n"
         "    <identifier name=\"k\" value=\"2\"/>\n"
         "    <identifier name=\"Tau\" value=\"0.5\"/>\n"
         "  </identifiers>\n"
         "  <blocks>\n" +
         blocks + "  </blocks>\n  <connections>" + connections +
         "</connections>\n"
         "  <solver t_end=\"" +
         std::to_string(t_end) +
         "\" rtol=\"1e-10\" atol=\"1e-12\"/>\n"
         "  <output interval=\"0.1\">" +
         logs + "</output>\n</diagram>\n";
}

// x' = -x/tau + k, x(0) = 3: x = k tau + (3 - k tau) exp(-t/tau). The code
// names the identifiers in another case (TAU, K) and reads them through a
// local helper, so upvalues reach nested functions.
TEST(LuaBlockTest, StateFollowsClosedForm) {
  const auto run = RunXml(Diagram(R"(    <block type="lua" name="lag" states="x" initial="3">
      local function rate(x) return -x/TAU + K end
      function derivatives(t, x) return rate(x) end
      function outputs(t, x) return x end
    </block>
)",
                                  "", R"(<log signal="lag.y" label="x"/>)", 2.0));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto t = run.Column("time"), x = run.Column("x");
  ASSERT_EQ(t.size(), 21u);
  const double k = 2, tau = 0.5;
  double worst = 0;
  for (std::size_t i = 0; i < t.size(); ++i)
    worst = std::max(worst, std::abs(x[i] - (k * tau + (3 - k * tau) * std::exp(-t[i] / tau))));
  EXPECT_LT(worst, 1e-8);  // rtol 1e-10 on values of order 1, over 20 steps' worth of error
}

// A decaying state with an input: x' = (u - x)/tau with u = k sin(t) from an
// expression block; closed form of the driven first-order lag.
TEST(LuaBlockTest, DrivenStateMatchesClosedForm) {
  const auto run = RunXml(Diagram(R"(    <block type="expression" name="u" inputs="" expr="k*sin(1*t)*1"/>
    <block type="lua" name="lag" inputs="u" states="x" feedthrough="none">
      function derivatives(t, x, u) return (u - x)/tau end
      function outputs(t, x, u) return x end
    </block>
)",
                                  R"(<connect from="u.y" to="lag.u"/>)", R"(<log signal="lag.y" label="x"/>)", 3.0));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto t = run.Column("time"), x = run.Column("x");
  // tau x' + x = k sin t, x(0) = 0:
  // x = k/(1 + tau^2) (sin t - tau cos t + tau exp(-t/tau))
  const double k = 2, tau = 0.5;
  double worst = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double exact =
        k / (1 + tau * tau) * (std::sin(t[i]) - tau * std::cos(t[i]) + tau * std::exp(-t[i] / tau));
    worst = std::max(worst, std::abs(x[i] - exact));
  }
  EXPECT_LT(worst, 1e-8);  // rtol 1e-10, atol 1e-12 on values of order 1
}

// Ports with widths: one input of width 2 gives two arguments; two outputs
// (widths 1 and 2) take three return values in port order.
TEST(LuaBlockTest, PortWidthsMapToArgumentsAndResults) {
  const auto run = RunXml(Diagram(R"(    <block type="constant" name="c" value="3 4"/>
    <block type="lua" name="f" inputs="u:2" outputs="norm parts:2">
      function outputs(t, a, b) return math.sqrt(a*a + b*b), a + t, b - t end
    </block>
)",
                                  R"(<connect from="c.y" to="f.u"/>)",
                                  R"(<log signal="f.norm" label="n"/><log signal="f.parts" label="p"/>)"));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto t = run.Column("time"), n = run.Column("n"), p0 = run.Column("p[0]"), p1 = run.Column("p[1]");
  for (std::size_t i = 0; i < t.size(); ++i) {
    EXPECT_DOUBLE_EQ(n[i], 5.0);
    EXPECT_DOUBLE_EQ(p0[i], 3.0 + t[i]);
    EXPECT_DOUBLE_EQ(p1[i], 4.0 - t[i]);
  }
}

// Feedthrough as declared: "y:u" makes y depend on u only; "none" on none;
// no attribute: every output on every input.
TEST(LuaBlockTest, FeedthroughAsDeclared) {
  const std::string code = "function outputs(t, u, v) return u, 0 end\n";
  const auto with = [&](const std::string& feedthrough) {
    return Diagram("    <block type=\"constant\" name=\"c\" value=\"1\"/>\n"
                   "    <block type=\"lua\" name=\"f\" inputs=\"u v\" outputs=\"y z\"" +
                       feedthrough + ">" + code + "</block>\n",
                   "<connect from=\"c.y\" to=\"f.u\"/><connect from=\"c.y\" to=\"f.v\"/>", "");
  };
  const auto declared = LoadXml(with(" feedthrough=\"y:u z:u,v\""));
  const blocks::Block& f = declared.diagram->block(declared.diagram->FindBlock("f"));
  EXPECT_TRUE(f.HasFeedthrough(0, 0));
  EXPECT_FALSE(f.HasFeedthrough(1, 0));
  EXPECT_TRUE(f.HasFeedthrough(0, 1));
  EXPECT_TRUE(f.HasFeedthrough(1, 1));
  const auto none = LoadXml(with(" feedthrough=\"none\""));
  const blocks::Block& g = none.diagram->block(none.diagram->FindBlock("f"));
  for (int in = 0; in < 2; ++in)
    for (int out = 0; out < 2; ++out) EXPECT_FALSE(g.HasFeedthrough(in, out));
  const auto all = LoadXml(with(""));
  const blocks::Block& h = all.diagram->block(all.diagram->FindBlock("f"));
  for (int in = 0; in < 2; ++in)
    for (int out = 0; out < 2; ++out) EXPECT_TRUE(h.HasFeedthrough(in, out));
}

// A Lua output fed back into its own input through its state only: declared
// without feedthrough, there is no loop, and x' = -k y with y = x decays as
// exp(-k t).
TEST(LuaBlockTest, OutputOfStateClosesNoLoop) {
  const auto run = RunXml(Diagram(R"(    <block type="lua" name="f" inputs="u" states="x" initial="1" feedthrough="none">
      function derivatives(t, x, u) return -k*u end
      function outputs(t, x, u) return x end
    </block>
)",
                                  R"(<connect from="f.y" to="f.u"/>)", R"(<log signal="f.y" label="x"/>)"));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  EXPECT_TRUE(run.loaded.diagram->loops().empty());
  const auto t = run.Column("time"), x = run.Column("x");
  for (std::size_t i = 0; i < t.size(); ++i) EXPECT_NEAR(x[i], std::exp(-2 * t[i]), 1e-8);
}

// An algebraic loop through two Lua blocks: g.y = u^3/4 (feedthrough), h.y =
// t + t^3/4 - u, g.u = h.y, h.u = g.y. So g.u + g.u^3/4 = t + t^3/4, whose one
// real root is g.u = t. The loop solver must find it at every output time.
TEST(LuaBlockTest, AlgebraicLoopThroughLuaBlocks) {
  const auto run = RunXml(Diagram(R"(    <block type="lua" name="g" inputs="u">
      function outputs(t, u) return u^3/4 end
    </block>
    <block type="lua" name="h" inputs="u" feedthrough="y:u">
      function outputs(t, u) return t + t^3/4 - u end
    </block>
)",
                                  R"(<connect from="g.y" to="h.u"/><connect from="h.y" to="g.u"/>)",
                                  R"(<log signal="h.y" label="root"/>)", 1.0));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  ASSERT_EQ(run.loaded.diagram->loops().size(), 1u);
  const auto t = run.Column("time"), root = run.Column("root");
  ASSERT_EQ(t.size(), 11u);
  // the loop converges to rel 1e-10 |z| + abs 1e-12 (AlgebraicLoop)
  for (std::size_t i = 0; i < t.size(); ++i) EXPECT_NEAR(root[i], t[i], 1e-9 * (1 + t[i])) << "t = " << t[i];
}

// Two output ports of different feedthrough in a loop: y reads only the
// state, z reads u; z feeds u through a gain. One `outputs` serves both
// ports; the cache must not hand z a value computed with a stale u.
// z = 1 - u and u = z/2 give z = 2/3, u = 1/3; x' = 1 - u = 2/3, so
// x = 1 + 2t/3.
TEST(LuaBlockTest, PortsOfDifferentFeedthroughInALoop) {
  const auto run = RunXml(Diagram(R"(    <block type="lua" name="f" inputs="u" outputs="y z" states="x" initial="1" feedthrough="z:u">
      function derivatives(t, x, u) return 1 - u end
      function outputs(t, x, u) return x, 1 - u end
    </block>
    <block type="gain" name="half" k="0.5"/>
)",
                                  R"(<connect from="f.z" to="half.u"/><connect from="half.y" to="f.u"/>)",
                                  R"(<log signal="f.y" label="x"/><log signal="f.z" label="z"/>)"));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto t = run.Column("time"), x = run.Column("x"), z = run.Column("z");
  for (std::size_t i = 0; i < t.size(); ++i) {
    EXPECT_NEAR(z[i], 2.0 / 3.0, 1e-8) << "t = " << t[i];
    EXPECT_NEAR(x[i], 1 + 2.0 / 3.0 * t[i], 1e-8) << "t = " << t[i];
  }
}

// A changed identifier reaches the code, also through a helper function
// that is not itself `outputs`: the registered binder shares the upvalues.
TEST(LuaBlockTest, RebindingAnIdentifierReachesEveryFunction) {
  auto loaded = LoadXml(Diagram(R"(    <block type="lua" name="f">
      local function scale() return K end
      function outputs(t) return scale() + k end
    </block>
)",
                                "", R"(<log signal="f.y" label="y"/>)"));
  const auto run_once = [&] {
    blocks::Simulator sim(*loaded.diagram, loaded.solver, loaded.logged);
    EXPECT_TRUE(sim.Run().ok);
    return sim.results().Column(sim.results().FindColumn("y")).back();
  };
  EXPECT_DOUBLE_EQ(run_once(), 4.0);
  loaded.identifiers->Override("k", 5);
  loaded.identifiers->Evaluate(*loaded.lua);
  EXPECT_GE(RebindIdentifiers(loaded.lua->get(), *loaded.identifiers, {"k"}), 1);
  EXPECT_DOUBLE_EQ(run_once(), 10.0);
}

// Two blocks may define the same function names: each code has its own
// environment, and globals they set do not leak into the sandbox.
TEST(LuaBlockTest, BlocksHaveSeparateEnvironments) {
  const auto run = RunXml(Diagram(R"(    <block type="lua" name="a">
      offset = 1
      function outputs(t) return offset end
    </block>
    <block type="lua" name="b">
      offset = 2
      function outputs(t) return offset end
    </block>
)",
                                  "", R"(<log signal="a.y" label="a"/><log signal="b.y" label="b"/>)"));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  EXPECT_DOUBLE_EQ(run.Column("a").back(), 1.0);
  EXPECT_DOUBLE_EQ(run.Column("b").back(), 2.0);
  EXPECT_TRUE(run.loaded.lua->Run("assert(offset == nil and outputs == nil)", "=check", nullptr));
}

// Code from a file (src=): its own name and lines in messages.
TEST(LuaBlockTest, CodeFromFile) {
  const auto folder = std::filesystem::temp_directory_path() / "mechflow_lua_block_test";
  std::filesystem::create_directories(folder);
  std::ofstream(folder / "good.lua") << "function outputs(t) return 3*k end\n";
  std::ofstream(folder / "bad.lua") << "-- line 1\nfunction outputs(t)\n  return 3 +\nend\n";
  const auto xml = [](const std::string& src) {
    return Diagram("    <block type=\"lua\" name=\"f\" src=\"" + src + "\"/>\n", "", "<log signal=\"f.y\" label=\"y\"/>");
  };
  const std::string path = (folder / "d.xml").string();
  auto good = diagrams::LoadDiagramDescription(diagrams::ReadDiagramText(xml("good.lua"), path));
  blocks::Simulator sim(*good.diagram, good.solver, good.logged);
  ASSERT_TRUE(sim.Run().ok);
  EXPECT_DOUBLE_EQ(sim.results().Column(sim.results().FindColumn("y")).back(), 6.0);
  const std::string message = InputErrorOf(
      [&] { diagrams::LoadDiagramDescription(diagrams::ReadDiagramText(xml("bad.lua"), path)); });
  EXPECT_THAT(message, HasSubstr("d.xml:7: block 'f' (lua): the Lua code does not compile: "));
  EXPECT_THAT(message, HasSubstr("bad.lua:4: unexpected symbol near 'end'"));
  std::filesystem::remove_all(folder);
}

// --- bad input ----------------------------------------------------------------

std::string LoadError(const std::string& block) { return InputErrorOf([&] { LoadXml(Diagram(block, "", "")); }); }

// A syntax error in inline code names the XML file and the line of the error
// in it (the block starts on line 7 of the diagram, the bad line is 9).
TEST(LuaBlockTest, SyntaxErrorNamesTheXmlLine) {
  const std::string message = LoadError(R"(    <block type="lua" name="f">
      function outputs(t)
        return 1 +* 2
      end
    </block>
)");
  EXPECT_THAT(message, HasSubstr("test.xml:7: block 'f' (lua): the Lua code does not compile: test.xml:9: "
                                 "unexpected symbol near '*'"));
}

// Code in CDATA may use '<' unescaped; its lines are still the file's.
TEST(LuaBlockTest, CdataCodeAndItsLines) {
  const auto run = RunXml(Diagram(R"(    <block type="lua" name="f"><![CDATA[
      function outputs(t) if t < 0.5 then return 1 else return 2 end end
    ]]></block>
)",
                                  "", R"(<log signal="f.y" label="y"/>)"));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  EXPECT_DOUBLE_EQ(run.Column("y").front(), 1.0);
  EXPECT_DOUBLE_EQ(run.Column("y").back(), 2.0);
  EXPECT_THAT(LoadError(R"(    <block type="lua" name="f">
      <![CDATA[
      function outputs(t) if t < then return 1 end end
    ]]></block>
)"),
              HasSubstr("does not compile: test.xml:9: unexpected symbol near 'then'"));
}

TEST(LuaBlockTest, MissingOrSurplusFunctions) {
  EXPECT_THAT(LoadError("<block type=\"lua\" name=\"f\">function output(t) return 1 end</block>\n"),
              HasSubstr("block 'f' (lua): the Lua code defines no function 'outputs'; expected "
                        "outputs(t, states..., inputs...) returning the outputs"));
  EXPECT_THAT(LoadError("<block type=\"lua\" name=\"f\" states=\"x\">function outputs(t, x) return x end</block>\n"),
              HasSubstr("defines no function 'derivatives'"));
  EXPECT_THAT(LoadError("<block type=\"lua\" name=\"f\">outputs = 3</block>\n"),
              HasSubstr("defines no function 'outputs' (it is a number)"));
  EXPECT_THAT(LoadError("<block type=\"lua\" name=\"f\">function outputs(t) return 1 end\n"
                        "function derivatives(t) return 1 end</block>\n"),
              HasSubstr("defines 'derivatives' but the block declares no states"));
  EXPECT_THAT(LoadError("<block type=\"lua\" name=\"f\"/>\n"), HasSubstr("no Lua code"));
  EXPECT_THAT(LoadError("<block type=\"lua\" name=\"f\">error('at load')</block>\n"),
              HasSubstr("the Lua code fails when it runs at load: test.xml:7: at load"));
}

TEST(LuaBlockTest, BadDeclarations) {
  const std::string code = ">function outputs(t) return 1 end</block>\n";
  EXPECT_THAT(LoadError("<block type=\"lua\" name=\"f\" inputs=\"u u\"" + code),
              HasSubstr("input name 'u' is given twice"));
  EXPECT_THAT(LoadError("<block type=\"lua\" name=\"f\" inputs=\"u:0\"" + code),
              HasSubstr("input 'u:0': the width after ':' must be a whole number from 1 to 1000"));
  EXPECT_THAT(LoadError("<block type=\"lua\" name=\"f\" outputs=\"end\"" + code),
              HasSubstr("output name 'end' must be a Lua name"));
  EXPECT_THAT(LoadError("<block type=\"lua\" name=\"f\" outputs=\"\"" + code),
              HasSubstr("a lua block needs at least one output"));
  EXPECT_THAT(LoadError("<block type=\"lua\" name=\"f\" states=\"x y\" initial=\"1\"" + code),
              HasSubstr("initial has 1 value(s) for 2 state(s)"));
  EXPECT_THAT(LoadError("<block type=\"lua\" name=\"f\" inputs=\"u\" feedthrough=\"z:u\"" + code),
              HasSubstr("feedthrough 'z:u': expected output:input[,input...] with an output of y"));
  EXPECT_THAT(LoadError("<block type=\"lua\" name=\"f\" inputs=\"u\" feedthrough=\"y:w\"" + code),
              HasSubstr("feedthrough 'y:w': 'w' is not an input; inputs: u"));
  EXPECT_THAT(LoadError("<block type=\"gain\" name=\"g\" k=\"1\">return 1</block>\n"),
              HasSubstr("test.xml:7: block 'g' (gain) takes no text content"));
  EXPECT_THAT(LoadError("<block type=\"lua\" name=\"f\" src=\"nowhere.lua\"" + code),
              HasSubstr("file 'nowhere.lua' not found"));
}

// --- errors during the run ----------------------------------------------------

std::string RunFailure(const std::string& block) {
  const auto run = RunXml(Diagram(block, "", ""));
  EXPECT_FALSE(run.outcome.ok);
  return run.outcome.failure;
}

// A Lua error names the block, the function, time and values, the Lua line
// in the XML file, and carries a traceback.
TEST(LuaBlockTest, RuntimeErrorNamesBlockLineAndTraceback) {
  const std::string failure = RunFailure(R"(    <block type="lua" name="pd" states="x">
      local function check(x)
        if t_bad then return 1 end
        return nil + x
      end
      function derivatives(t, x) local r = check(x); return r end
      function outputs(t, x) return x end
    </block>
)");
  EXPECT_THAT(failure, HasSubstr("block 'pd': Lua function derivatives at t = 0, x = 0: test.xml:10: attempt to "
                                 "perform arithmetic on a nil value"));
  EXPECT_THAT(failure, HasSubstr("stack traceback:"));
  EXPECT_THAT(failure, HasSubstr("test.xml:12: in "));
}

TEST(LuaBlockTest, WrongNumberOfValues) {
  EXPECT_THAT(RunFailure("<block type=\"lua\" name=\"f\" outputs=\"a b\">function outputs(t) return 1 end</block>\n"),
              HasSubstr("block 'f': Lua function outputs at t = 0: returned 1 value, expected 2 (one per output "
                        "value)"));
  EXPECT_THAT(RunFailure("<block type=\"lua\" name=\"f\" states=\"x\">function outputs(t, x) return x end "
                         "function derivatives(t, x) return 1, 2 end</block>\n"),
              HasSubstr("Lua function derivatives at t = 0, x = 0: returned 2 values, expected 1 (one per state)"));
}

TEST(LuaBlockTest, NonFiniteOrNonNumberValues) {
  EXPECT_THAT(RunFailure("<block type=\"lua\" name=\"f\">function outputs(t) return 1/(t - t) end</block>\n"),
              HasSubstr("block 'f': Lua function outputs at t = 0: value 1 is "));
  EXPECT_THAT(RunFailure("<block type=\"lua\" name=\"f\">function outputs(t) return 1/(t - t) end</block>\n"),
              HasSubstr(", not a finite number"));
  EXPECT_THAT(RunFailure("<block type=\"lua\" name=\"f\">function outputs(t) return 'one' end</block>\n"),
              HasSubstr("value 1 is a string, not a finite number"));
}

// Code that may loop only through a call (recursion in tail position runs
// forever without growing the stack) is bounded too: the straight-line
// shortcut must not take it.
TEST(LuaBlockTest, RecursionThroughCallsIsBounded) {
  for (const std::string code : {
           "function outputs(t) return outputs(t) end",
           "local function f(t) return f(t) end function outputs(t) return f(t) end",
           "local a, sin, b\nfunction outputs(t) a, sin, b = 0, outputs, 0; return sin(t) end",
       }) {
    EXPECT_THAT(RunFailure("<block type=\"lua\" name=\"f\">" + code + "</block>\n"),
                HasSubstr("instruction limit exceeded"))
        << code;
  }
}

// Without `outputs`, a block with states outputs its states (no Lua call).
TEST(LuaBlockTest, OutputsDefaultToStates) {
  const auto run = RunXml(Diagram(R"(    <block type="lua" name="f" outputs="p:2" states="x v" initial="1 0">
      function derivatives(t, x, v) return v, -4*x end
    </block>
)",
                                  "", R"(<log signal="f.p" label="p"/>)"));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto t = run.Column("time"), x = run.Column("p[0]"), v = run.Column("p[1]");
  for (std::size_t i = 0; i < t.size(); ++i) {  // x'' = -4x: x = cos 2t
    EXPECT_NEAR(x[i], std::cos(2 * t[i]), 1e-8);
    EXPECT_NEAR(v[i], -2 * std::sin(2 * t[i]), 1e-8);
  }
  EXPECT_THAT(LoadError("<block type=\"lua\" name=\"f\" states=\"x v\">"
                        "function derivatives(t, x, v) return v, -x end</block>\n"),
              HasSubstr("the code defines no function 'outputs', so the outputs are the states, but the outputs "
                        "have 1 value(s) for 2 state(s)"));
}

// An endless loop ends the run through the instruction limit.
TEST(LuaBlockTest, EndlessLoopIsStopped) {
  EXPECT_THAT(RunFailure("<block type=\"lua\" name=\"f\">function outputs(t)\nwhile true do end\nend</block>\n"),
              HasSubstr("block 'f': Lua function outputs at t = 0: test.xml:8: instruction limit exceeded"));
}

}  // namespace
}  // namespace mechflow::scripting::lua_block_test
