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

#include "scripting/compiled_expression.h"
#include "scripting/identifiers.h"
#include "scripting/lua_state.h"
#include "tests/test_util.h"

namespace mechflow::scripting {
namespace {

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
                "string.find: the pattern '.-.-.-.-.-.-.-.-.-.-b' may backtrack", 0.5);
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

}  // namespace
}  // namespace mechflow::scripting
