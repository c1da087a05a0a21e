// Lua from someone else that tries to hang a run: by swallowing the limit's
// error, by C functions the instruction count does not see, by finalizers
// that run with hooks off, by metatables that the straight-line fast path
// would reach, and by timers too fine to get through. Each ends within a
// second or two with a clear error, and the state (or the run's rows) stays.

#include <chrono>
#include <cmath>
#include <functional>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <lua.hpp>

#include "mech/errors.h"
#include "scripting/compiled_expression.h"
#include "scripting/identifiers.h"
#include "scripting/lua_state.h"
#include "tests/test_util.h"

namespace mechflow::scripting::hostile_code_test {  // names of its own: the files of its folder are compiled together
namespace {

using mechflow::testing::InputErrorOf;
using mechflow::testing::RunXml;
using ::testing::HasSubstr;

// Wall-clock seconds `f` takes.
double Seconds(const std::function<void()>& f) {
  const auto start = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string RunScript(LuaState& lua, const std::string& code) {
  std::string error;
  return lua.Run(code, "@script.lua", &error) ? "" : error;
}

// Runs `code`, expects an error containing `expected` within `bound` seconds,
// and that the state still works.
void ExpectStopped(LuaState& lua, const std::string& code, const std::string& expected, double bound = 2.0) {
  std::string error;
  const double seconds = Seconds([&] { error = RunScript(lua, code); });
  EXPECT_THAT(error, HasSubstr(expected)) << code;
  EXPECT_LT(seconds, bound) << code;
  std::printf("[ measured ] %.3f s: %s\n", seconds, code.substr(0, 60).c_str());
  EXPECT_EQ(RunScript(lua, "assert(math.sqrt(16) == 4)"), "");
  EXPECT_EQ(lua_gettop(lua.get()), 0);
}

TEST(HostileCodeTest, PcallCannotSwallowTheInstructionLimit) {
  LuaState lua;
  const char* limit = "instruction limit exceeded";
  ExpectStopped(lua, "while true do pcall(function() while true do end end) end", limit);
  // nested catches, an error handler that loops, and a loop in a reader
  ExpectStopped(lua, "while true do pcall(function() while true do pcall(function() while true do end end) end end) end",
                limit);
  ExpectStopped(lua, "while true do xpcall(function() while true do end end, function() while true do end end) end",
                limit);
  ExpectStopped(lua, "while true do load(function() while true do end end) end", limit);
  ExpectStopped(lua, "local t = {3, 2, 1} while true do pcall(table.sort, t, function() while true do end end) end",
                limit);
}

TEST(HostileCodeTest, WallClockLimitStopsCodeThatLivesInCFunctions) {
  LuaState lua;
  lua.set_time_limit(0.3);
  // few instructions, each a costly C call: the count alone would take
  // minutes, and its checks alone overran the limit by a thousand such calls
  // (2.1 s under the sanitizers); the allocations look at the clock too
  ExpectStopped(lua, "for i = 1, 1e9 do local s = string.rep('x', 1 << 20) end", "time limit exceeded", 1.0);
  ExpectStopped(lua, "while true do pcall(string.rep, 'x', 1 << 20) end", "time limit exceeded", 1.0);
}

TEST(HostileCodeTest, CFunctionsTheCountCannotSeeAreBounded) {
  LuaState lua;
  const double empty = Seconds([&] {
    EXPECT_EQ(RunScript(lua, "assert(string.rep('', 2^53) == '' and ('').rep('', 2^53, '') == '')"), "");
  });
  EXPECT_LT(empty, 0.1);
  EXPECT_EQ(RunScript(lua, "assert(string.rep('ab', 2, ',') == 'ab,ab')"), "");
  ExpectStopped(lua, "table.move({}, 1, 2^53, 2)",
                "table.move: 9.0072e+15 elements are more than a table can hold under the memory limit (1.67772e+07)",
                0.5);
  ExpectStopped(lua, "table.move({}, 1, math.maxinteger, 2)", "more than a table can hold", 0.5);
  EXPECT_EQ(RunScript(lua, "local t = table.move({1, 2, 3}, 1, 3, 2) assert(t[4] == 3)"), "");
  // exponential backtracking: refused before it starts
  ExpectStopped(lua, "string.find(string.rep('a', 40), '.-.-.-.-.-.-.-.-.-.-b')",
                "string.find: the pattern '.-.-.-.-.-.-.-.-.-.-b' may take about", 0.5);
  ExpectStopped(lua, "for w in string.gmatch(string.rep('a', 1e5), 'a*a*b') do end", "string.gmatch: the pattern",
                0.5);
  ExpectStopped(lua, "local s = string.rep('a', 1e5) s:gsub('a*b', '')", "string.gsub: the pattern", 0.5);
  // optional items double the ways to match: 2^40 for this one
  ExpectStopped(lua, "string.match(string.rep('a', 40), string.rep('a?', 40) .. string.rep('a', 40))",
                "string.match: the pattern", 0.5);
  // what scripts do every day still works: linear patterns, anchored ones, plain finds
  EXPECT_EQ(RunScript(lua, "local s = string.rep('a', 1e6) .. 'b'\n"
                           "assert(s:find('b', 1, true) == 1e6 + 1 and s:find('ab') == 1e6)\n"
                           "assert(('x = 12.5'):match('^(%w+)%s*=%s*([%d.]+)$') == 'x')\n"
                           "assert(select(2, ('a,b,c'):gsub('[^,]+', '')) == 3)"),
            "");
}

TEST(HostileCodeTest, FinalizersAreRefused) {
  {
    LuaState lua;
    ExpectStopped(lua, "setmetatable({}, {__gc = function() while true do end end})",
                  "setmetatable: finalizers (__gc) are not allowed", 0.5);
    // a __gc added later is never called (Lua marks objects at setmetatable)
    EXPECT_EQ(RunScript(lua, "local mt = {} x = setmetatable({}, mt) mt.__gc = function() while true do end end"),
              "");
    EXPECT_EQ(RunScript(lua, "x = nil collectgarbage()"), "");
  }  // closing the state runs no finalizer either
}

TEST(HostileCodeTest, StringAndGlobalMetatablesAreProtected) {
  LuaState lua;
  EXPECT_EQ(RunScript(lua, "assert(getmetatable('') == false and getmetatable(_G) == false)"), "");
  ExpectStopped(lua, "getmetatable('').__add = function() while true do end end", "attempt to index a boolean value",
                0.5);
  ExpectStopped(lua, "setmetatable(_G, {__index = function() while true do end end})",
                "cannot change a protected metatable", 0.5);
  ExpectStopped(lua, "string.len = function() while true do end end return ('x'):len()", "instruction limit exceeded");

  // a straight-line expression doing string arithmetic still runs the library's own metamethod
  IdentifierTable ids;
  ids.Evaluate(lua);
  const CompiledExpression e(lua, "tostring(x) + 1", {"x"}, ids, "=block 'f'");
  const double x = 2.0;
  EXPECT_EQ(e.Evaluate(&x), 3.0);
}

// A diagram with a control script `script`, from t = t0 to t0 + 1.
std::string Diagram(const std::string& script, double t0 = 0.0) {
  return R"(<diagram name="d">
  <blocks><block type="integrator" name="x"/><block type="constant" name="one" value="1"/></blocks>
  <connections><connect from="one.y" to="x.u"/></connections>
  <script>)" + script + R"(</script>
  <solver t_start=")" + std::to_string(t0) + R"(" t_end=")" + std::to_string(t0 + 1) + R"("/>
  <output interval="0.1"><log signal="x.y" label="x"/></output>
</diagram>)";
}

TEST(HostileCodeTest, ARunWhoseScriptSwallowsTheLimitEndsWithItsRows) {
  for (const char* script :
       {"function init(sim) while true do pcall(function() while true do end end) end end",
        "function init(sim) sim:every(0.25, function() while true do pcall(function() while true do end end) end "
        "end) end"}) {
    mechflow::testing::XmlRun run;
    const double seconds = Seconds([&] { run = RunXml(Diagram(script)); });
    ASSERT_FALSE(run.outcome.ok) << script;
    EXPECT_THAT(run.outcome.failure, HasSubstr("instruction limit exceeded")) << script;
    EXPECT_LT(seconds, 2.0) << script;
  }
  // the timer at 0.25 failed: rows up to there are kept
  auto run =
      RunXml(Diagram("function init(sim) sim:every(0.25, function() while true do pcall(error) end end, 0.25) end"));
  ASSERT_FALSE(run.outcome.ok);
  EXPECT_EQ(run.sim->results().num_rows(), 3);  // 0, 0.1, 0.2
}

TEST(HostileCodeTest, TimersTooFineToGetThroughAreRefused) {
  auto fine = RunXml(Diagram("function init(sim) sim:every(1e-12, function() end) end"));
  ASSERT_FALSE(fine.outcome.ok);
  EXPECT_THAT(fine.outcome.failure,
              HasSubstr("sim:every: the period 1e-12 s is too small for the run from t = 0 to 1 s (more than 1e8 "
                        "instants in the run); use at least 1e-08 s"));
  // below the spacing of doubles at t = 1e9
  auto below_ulp = RunXml(Diagram("function init(sim) sim:every(1e-8, function() end) end", 1e9));
  ASSERT_FALSE(below_ulp.outcome.ok);
  EXPECT_THAT(below_ulp.outcome.failure, HasSubstr("cannot be told apart in double precision"));
  auto many = RunXml(Diagram("function init(sim) for i = 1, 20000 do sim:every(1, function() end) end end"));
  ASSERT_FALSE(many.outcome.ok);
  EXPECT_THAT(many.outcome.failure, HasSubstr("sim:every: a script may have at most 10000 timers"));
}

// A diagram whose control script defines the globals `script` makes, and whose
// Lua block `block` computes y from u = 1.
std::string BlockDiagram(const std::string& script, const std::string& block) {
  return R"(<diagram name="d">
  <blocks><block type="constant" name="one" value="1"/>
    <block type="lua" name="f" inputs="u"><![CDATA[)" + block + R"(]]></block></blocks>
  <connections><connect from="one.y" to="f.u"/></connections>
  <script><![CDATA[)" + script + R"(]]></script>
  <solver t_end="1"/>
  <output interval="0.5"><log signal="f.y" label="y"/></output>
</diagram>)";
}

TEST(HostileCodeTest, StraightLineCodeReachingAScriptsMetatableIsBounded) {
  // each loops forever in a metamethod or call that straight-line code
  // reaches; the code itself cannot loop, so it once ran without the count
  const std::string loop = "function() while true do end end";
  const std::string looping = "T = setmetatable({}, {__index = " + loop + ", __add = " + loop + ", __len = " + loop +
                              ", __lt = " + loop + ", __call = " + loop + "})\n";
  const struct {
    const char* script;
    const char* block;
  } cases[] = {
      {"", "function outputs(t, u) return T.x end"},
      {"", "function outputs(t, u) return T + u end"},
      {"", "function outputs(t, u) return #T end"},
      {"", "function outputs(t, u) return (T < u) and 1 or 0 end"},
      {"", "local P = T\nfunction outputs(t, u) return P.x end"},  // kept at load
      {"", "function outputs(t, u) local p = {T} return p[1].x end"},
      {"sin = T\n", "function outputs(t, u) return sin(u) end"},  // a sandbox name rebound
      {"pi = T\n", "function outputs(t, u) return pi + u end"},
      {"S = string\n", "function outputs(t, u) return #S.rep end"},  // no loop: still bounded, still right
  };
  for (const auto& c : cases) {
    const std::string script = looping + c.script;
    mechflow::testing::XmlRun run;
    const double seconds = Seconds([&] { run = RunXml(BlockDiagram(script, c.block)); });
    if (std::string(c.script).rfind("S =", 0) == 0) {
      EXPECT_FALSE(run.outcome.ok) << c.block;  // the length of a function is an error
      EXPECT_THAT(run.outcome.failure, HasSubstr("attempt to get length of a function value")) << c.block;
    } else {
      ASSERT_FALSE(run.outcome.ok) << c.block;
      EXPECT_THAT(run.outcome.failure, HasSubstr("instruction limit exceeded")) << c.block;
    }
    EXPECT_LT(seconds, 2.0) << c.block;
    std::printf("[ measured ] %.3f s: %s\n", seconds, c.block);
  }
  // a global that is a number stays on the fast path and right
  const auto number = RunXml(BlockDiagram("K = 2", "function outputs(t, u) return K * u end"));
  ASSERT_TRUE(number.outcome.ok) << number.outcome.failure;
}

TEST(HostileCodeTest, StraightLineExpressionsCallOnlyFunctionsOfNumbers) {
  LuaState lua;
  // a C function the script took from the library: load reads the chunk from it
  ASSERT_EQ(RunScript(lua, "g = string.gmatch('while true do end', '.+')\n"
                           "h = string.gmatch('while true do end', '.+')\n"
                           "sqrt = pcall"),
            "");
  IdentifierTable ids;
  ids.Evaluate(lua);
  const double x = 1.0;
  for (const char* text : {"load(g)()", "sqrt(load(h))"}) {
    const CompiledExpression e(lua, text, {"x"}, ids, "=block 'f'");
    std::string error;
    const double seconds = Seconds([&] {
      try {
        e.Evaluate(&x);
      } catch (const SimulationError& failure) {
        error = failure.what();
      }
    });
    EXPECT_THAT(error, HasSubstr("instruction limit exceeded")) << text;
    EXPECT_LT(seconds, 2.0) << text;
  }
  // the sandbox's functions of numbers keep the fast path: with a limit of
  // one instruction, only an expression that runs without the count succeeds
  const CompiledExpression fast(lua, "abs(cos(x)) + min(x, 2) * pi", {"x"}, ids, "=block 'f'");
  const CompiledExpression counted(lua, "select(1, x)", {"x"}, ids, "=block 'f'");
  lua.set_instruction_limit(1);
  EXPECT_NEAR(fast.Evaluate(&x), std::abs(std::cos(1.0)) + M_PI, 1e-12);
  EXPECT_THROW(counted.Evaluate(&x), SimulationError);
}

TEST(HostileCodeTest, PlainFindsAreLinear) {
  LuaState lua;
  // Lua's own search compares the needle at every position: 1e12 byte
  // comparisons here (minutes); the guard's search is linear
  const double seconds = Seconds([&] {
    EXPECT_EQ(RunScript(lua, "local s = string.rep('a', 1e7) .. 'b'\n"
                             "local p = string.rep('a', 1e5) .. 'b'\n"
                             "assert(string.find(s, p, 1, true) == 1e7 - 1e5 + 1)\n"
                             "assert(select(2, s:find(p)) == 1e7 + 1)\n"  // no special characters: plain too
                             "assert(s:find(p .. 'c', 1, true) == nil)\n"
                             "assert(s:find(p, -1e5 - 1, true) == 1e7 - 1e5 + 1 and s:find(p, -1e5, true) == nil)\n"
                             "assert(s:find('', 5, true) == 5 and s:find('', 1e9, true) == nil)"),
              "");
  });
  EXPECT_LT(seconds, 2.0);
  std::printf("[ measured ] %.3f s: plain finds of 1e5 bytes in 1e7\n", seconds);
  // a pattern without repetitions still compares itself at every position: n m steps
  ExpectStopped(lua, "local s = string.rep('a', 1e7) string.match(s, string.rep('a', 1e5) .. 'b.')",
                "string.match: the pattern 'aaaa", 2.0);
  // a repetition followed by a long tail: n^2 m steps
  ExpectStopped(lua, "local s = string.rep('a', 1e4) string.find(s, 'a*' .. string.rep('a', 1e4) .. 'b')",
                "string.find: the pattern 'a*aaa", 0.5);
  // a back-reference compares a capture as long as the subject
  ExpectStopped(lua, "local s = string.rep('a', 1e4) string.find(s, '(a-)%1b')", "string.find: the pattern", 0.5);
}

TEST(HostileCodeTest, TableFunctionsRefuseALengthNoTableHolds) {
  LuaState lua;
  const std::string huge = "local t = setmetatable({}, {__len = function() return 2^53 end})\n";
  // each would loop in C over 2^53 nils (or sort them with a C comparator)
  ExpectStopped(lua, huge + "table.insert(t, 1, 'x')",
                "table.insert: the length 9.0072e+15 (from the table's __len) is more than a table can hold", 0.5);
  ExpectStopped(lua, huge + "table.remove(t, 1)", "table.remove: the length 9.0072e+15", 0.5);
  ExpectStopped(lua, "local t = setmetatable({}, {__len = function() return 2^31 - 2 end}) table.sort(t, pcall)",
                "table.sort: the length 2.14748e+09", 0.5);
  ExpectStopped(lua, "table.concat({}, '', 1, 2^40)", "table.concat: 1.09951e+12 elements are more than", 0.5);
  ExpectStopped(lua, huge + "table.concat(t)", "table.concat: the length 9.0072e+15", 0.5);
  // ordinary uses, and a __len within reach, still work
  EXPECT_EQ(RunScript(lua, "local t = {3, 1, 2} table.insert(t, 1, 0) table.sort(t) assert(table.remove(t, 1) == 0)\n"
                           "assert(table.concat(t, ',') == '1,2,3' and table.concat(t, ',', 2, 3) == '2,3')\n"
                           "local u = setmetatable({}, {__len = function() return 2^53 end}) table.insert(u, 'x')\n"
                           "local v = setmetatable({1, 2}, {__len = function() return 2 end}) table.insert(v, 1, 0)\n"
                           "assert(v[3] == 2)"),
            "");
}

TEST(HostileCodeTest, ChunksThatCompileInQuadraticTimeAreRefused) {
  LuaState lua;
  // Lua's compiler walks the jump list of an and/or chain at each operator:
  // 1e5 of them take about 17 s, a million half an hour
  ExpectStopped(lua, "load('return ' .. string.rep('x and ', 1e5) .. 'x')",
                "load: the chunk has 100000 'and'/'or', 0 'elseif' and 0 goto, break and labels", 0.5);
  ExpectStopped(lua, "load('if x then ' .. string.rep('elseif x then ', 1e5) .. 'end')", "100000 'elseif'", 0.5);
  // a reader function is read whole first
  ExpectStopped(lua, "local n = 0 load(function() n = n + 1 return n <= 1e5 and 'x or ' or n == 1e5 + 1 and 'x' or nil end)",
                "load: the chunk has 100000 'and'/'or'", 1.0);
  // the script itself, and an expression
  const std::string chain = "return " + [] {
    std::string s;
    for (int i = 0; i < 100000; ++i) s += "x or ";
    return s;
  }() + "x";
  const double seconds = Seconds([&] { EXPECT_THAT(RunScript(lua, chain), HasSubstr("script.lua: the chunk has")); });
  EXPECT_LT(seconds, 0.5);
  IdentifierTable ids;
  ids.Evaluate(lua);
  EXPECT_THAT(InputErrorOf([&] { CompiledExpression(lua, chain.substr(7), {"x"}, ids, "=block 'f'"); }),
              HasSubstr("block 'f': expression 'x or x or"));
  // ordinary chunks, and a reader's, still load
  EXPECT_EQ(RunScript(lua, "local parts = {'return ', '1 and ', '2'} local i = 0\n"
                           "local f = load(function() i = i + 1 return parts[i] end) assert(f() == 2)\n"
                           "assert(load('return 1 or 2')() == 1)"),
            "");
}

TEST(HostileCodeTest, AGuardsRefusalCannotBeCaught) {
  LuaState lua;
  // the refusal is raised again at the next instruction, as a limit's error
  EXPECT_THAT(RunScript(lua, "local s = string.rep('a', 1e5) local ok = pcall(string.match, s, 'a*a*a*b') x = 1"),
              HasSubstr("string.match: the pattern 'a*a*a*b'"));
  EXPECT_EQ(RunScript(lua, "assert(x == nil)"), "");
  EXPECT_THAT(RunScript(lua, "local ok = pcall(table.concat, {}, '', 1, 2^40) x = 1"),
              HasSubstr("table.concat: 1.09951e+12 elements"));
  EXPECT_EQ(RunScript(lua, "assert(x == nil)"), "");
}

TEST(HostileCodeTest, LoopsOfFullCollectionsMeetTheTimeLimit) {
  LuaState lua;
  // a heap of half a million tables: each full collection takes tens of ms, and a
  // loop of them ran a thousand instructions (hundreds of collections) between
  // two looks at the clock
  ASSERT_EQ(RunScript(lua, "big = {} for i = 1, 5e5 do big[i] = {} end"), "");
  ASSERT_EQ(RunScript(lua, "s = string.rep('x', 1 << 25)"), "");
  lua.set_time_limit(0.3);
  ExpectStopped(lua, "while true do collectgarbage() end", "time limit exceeded", 1.0);
  // a refused allocation collects the whole heap first (Lua's own allocations
  // do: here the string of 256 MiB that `..` would make)
  ExpectStopped(lua, "while true do pcall(function() return s .. s .. s .. s .. s .. s .. s .. s end) end",
                "time limit exceeded", 1.0);
}

}  // namespace
}  // namespace mechflow::scripting::hostile_code_test
