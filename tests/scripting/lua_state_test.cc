// LuaState: the sandbox, the expression functions, the memory and instruction
// limits, and protected calls with a traceback.

#include "scripting/lua_state.h"

#include <cmath>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <lua.hpp>

namespace mechflow::scripting {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

// Runs `code`; returns "" or the error message (with its traceback).
std::string RunLua(LuaState& lua, const std::string& code, const std::string& chunk = "=test") {
  std::string error;
  return lua.Run(code, chunk, &error) ? "" : error;
}

// Evaluates the Lua expression `code` to a number.
double Number(LuaState& lua, const std::string& code) {
  lua_State* L = lua.get();
  const std::string chunk = "return " + code;
  std::string error;
  if (luaL_loadbufferx(L, chunk.data(), chunk.size(), "=number", "t") != LUA_OK || !lua.Call(0, 1, &error)) {
    ADD_FAILURE() << code << ": " << (error.empty() ? lua_tostring(L, -1) : error);
    lua_settop(L, 0);
    return NAN;
  }
  const double value = lua_tonumber(L, -1);
  lua_pop(L, 1);
  return value;
}

TEST(LuaStateTest, SandboxHasNoFilesProcessesOrModules) {
  LuaState lua;
  EXPECT_FALSE(lua.is_unsafe());
  for (const char* name : {"io", "os", "require", "package", "debug", "dofile", "loadfile", "coroutine"})
    EXPECT_EQ(RunLua(lua, std::string("assert(") + name + " == nil)"), "") << name;
  EXPECT_THAT(RunLua(lua, "os.execute('true')"), StartsWith("test:1: attempt to index a nil value (global 'os')"));
  // what expressions and scripts need is there
  for (const char* name : {"math", "string", "table", "utf8", "pcall", "error", "print", "load", "setmetatable"})
    EXPECT_EQ(RunLua(lua, std::string("assert(") + name + " ~= nil)"), "") << name;
  EXPECT_EQ(lua_gettop(lua.get()), 0);
}

TEST(LuaStateTest, LoadTakesTextOnly) {
  LuaState lua;
  // bytecode is refused whatever mode is asked for
  for (const char* mode : {"nil", "'b'", "'bt'"})
    EXPECT_EQ(RunLua(lua, std::string("local f, e = load(string.dump(function() return 1 end), 'x', ") + mode +
                              ")\nassert(f == nil and e == \"attempt to load a binary chunk (mode is 't')\", e)"),
              "")
        << mode;
  // text chunks work as usual, with the globals or with the given environment
  EXPECT_EQ(Number(lua, "load('return math.pi')()"), M_PI);
  EXPECT_EQ(Number(lua, "load('return x', 'chunk', 't', {x = 3})()"), 3.0);
  EXPECT_EQ(Number(lua, "select('#', load('return nil + 1'))"), 1.0);
  EXPECT_THAT(RunLua(lua, "assert(load('return x', 'chunk', 't', nil))()"),
              HasSubstr("attempt to index a nil value (upvalue '_ENV')"));  // an explicit nil env stays nil
}

TEST(LuaStateTest, UnsafeStateOpensEverythingButStillRefusesBytecode) {
  LuaState lua({.unsafe = true});
  EXPECT_TRUE(lua.is_unsafe());
  EXPECT_EQ(RunLua(lua, "assert(io and os and require and debug and coroutine and dofile)"), "");
  EXPECT_EQ(RunLua(lua, "assert(not load(string.dump(function() end)))"), "");
  EXPECT_EQ(Number(lua, "sqr(3)"), 9.0);
}

TEST(LuaStateTest, ExpressionFunctionsOfTheIdentifierGrammar) {
  LuaState lua;
  EXPECT_EQ(Number(lua, "sin(0.5)"), std::sin(0.5));
  EXPECT_EQ(Number(lua, "cos(0.5)"), std::cos(0.5));
  EXPECT_EQ(Number(lua, "tan(0.5)"), std::tan(0.5));
  EXPECT_EQ(Number(lua, "arcsin(0.5)"), std::asin(0.5));
  EXPECT_EQ(Number(lua, "arccos(0.5)"), std::acos(0.5));
  EXPECT_EQ(Number(lua, "arctan(0.5)"), std::atan(0.5));
  EXPECT_EQ(Number(lua, "asin(0.5) + acos(0.5) + atan(0.5)"), std::asin(0.5) + std::acos(0.5) + std::atan(0.5));
  EXPECT_EQ(Number(lua, "atan(1, -1)"), std::atan2(1, -1));
  EXPECT_EQ(Number(lua, "exp(2)"), std::exp(2.0));
  EXPECT_EQ(Number(lua, "ln(2)"), std::log(2.0));
  EXPECT_EQ(Number(lua, "log(2)"), std::log(2.0));
  EXPECT_EQ(Number(lua, "sqrt(2)"), std::sqrt(2.0));
  EXPECT_EQ(Number(lua, "sqr(-3)"), 9.0);
  EXPECT_EQ(Number(lua, "abs(-2.5)"), 2.5);
  EXPECT_EQ(Number(lua, "sign(-2) * 10 + sign(3)"), -9.0);
  EXPECT_EQ(Number(lua, "sign(0)"), 0.0);
  EXPECT_TRUE(std::isnan(Number(lua, "sign(0/0)")));  // NaN is not hidden
  EXPECT_EQ(Number(lua, "min(3, 1, 2) + max(3, 1, 2)"), 4.0);
  EXPECT_EQ(Number(lua, "floor(2.5) + ceil(2.5)"), 5.0);
  EXPECT_EQ(Number(lua, "pi"), M_PI);
  EXPECT_EQ(Number(lua, "sinh(0.5) + cosh(0.5)"), std::sinh(0.5) + std::cosh(0.5));
  // tanh is not in Lua 5.4's math; it must be accurate near 0 (friction
  // regularisation tanh(v / eps) lives there) and saturate cleanly
  EXPECT_EQ(Number(lua, "tanh(0.5)"), std::tanh(0.5));
  EXPECT_EQ(Number(lua, "tanh(1e-12)"), std::tanh(1e-12));
  EXPECT_EQ(Number(lua, "tanh(800) - tanh(-800)"), 2.0);
  // ^ is right-associative and binds tighter than unary minus, as in the grammar
  EXPECT_EQ(Number(lua, "2^3^2"), 512.0);
  EXPECT_EQ(Number(lua, "-2^2"), -4.0);
  EXPECT_EQ(Number(lua, "9.8696044E+5"), 986960.44);
  EXPECT_THAT(RunLua(lua, "return sqr('x')"), HasSubstr("bad argument #1 to 'sqr' (number expected, got string)"));
  EXPECT_TRUE(LuaState::IsBuiltinName("arctan"));
  EXPECT_TRUE(LuaState::IsBuiltinName("pi"));
  EXPECT_FALSE(LuaState::IsBuiltinName("math"));
  // the smooth step of the tension-mechanism paper: h0 to x0, a cubic, h1 from x1
  EXPECT_EQ(Number(lua, "STEP(-1, 0, 2, 1, 5)"), 2.0);
  EXPECT_EQ(Number(lua, "STEP(0.5, 0, 2, 1, 5)"), 3.5);
  EXPECT_EQ(Number(lua, "STEP(0.25, 0, 0, 1, 1)"), 0.25 * 0.25 * 2.5);
  EXPECT_EQ(Number(lua, "STEP(3, 0, 2, 1, 5)"), 5.0);
  EXPECT_EQ(Number(lua, "STEP(0, 0, 0, 0, 1) + STEP(1e-300, 0, 0, 0, 1)"), 1.0);  // x1 = x0: a jump, no NaN
  EXPECT_TRUE(std::isnan(Number(lua, "STEP(0/0, 0, 0, 1, 1)")));
  EXPECT_THAT(RunLua(lua, "return STEP(0, 1, 0, 0, 1)"), HasSubstr("STEP: x1 (0.0) is below x0 (1.0)"));
  EXPECT_EQ(LuaState::BuiltinNames().size(), 25u);
}

TEST(LuaStateTest, MemoryLimitStopsRunawayAllocation) {
  LuaState lua;
  EXPECT_EQ(lua.memory_limit(), std::size_t(256) << 20);
  lua.set_memory_limit(8 << 20);
  EXPECT_EQ(RunLua(lua, "local s = string.rep('x', 64 * 1024 * 1024)"), "not enough memory (Lua may use at most 8 MiB)");
  EXPECT_EQ(RunLua(lua, "local t = {} for i = 1, 1e8 do t[i] = i end"), "not enough memory (Lua may use at most 8 MiB)");
  EXPECT_LE(lua.memory_in_use(), std::size_t(8) << 20);
  // the state is still usable, and the memory comes back
  lua_gc(lua.get(), LUA_GCCOLLECT);
  EXPECT_LT(lua.memory_in_use(), std::size_t(1) << 20);
  EXPECT_EQ(Number(lua, "#string.rep('x', 1000)"), 1000.0);
}

TEST(LuaStateTest, InstructionLimitStopsEndlessLoops) {
  LuaState lua({.instruction_limit = 1'000'000});
  EXPECT_EQ(LuaState().instruction_limit(), 10'000'000);
  EXPECT_EQ(lua.instruction_limit(), 1'000'000);
  EXPECT_THAT(RunLua(lua, "while true do end"),
              StartsWith("test:1: instruction limit exceeded (1000000 instructions in one call; endless loop?)"));
  // catching the error does not escape the limit: it is raised again
  EXPECT_THAT(RunLua(lua, "for i = 1, 10 do pcall(function() while true do end end) end while true do end"),
              HasSubstr("instruction limit exceeded"));
  // the count is per call: ten calls of 200000 instructions each (an add and a
  // loop step per pass) run, two million in all
  for (int i = 0; i < 10; ++i)
    EXPECT_EQ(Number(lua, "(function() local n = 0 for i = 1, 1e5 do n = n + 1 end return n end)()"), 1e5) << i;
  // and the hook is gone between calls
  EXPECT_EQ(lua_gethook(lua.get()), nullptr);
  // without a limit, long loops run to the end
  lua.set_instruction_limit(0);
  EXPECT_EQ(Number(lua, "(function() local n = 0 for i = 1, 3e6 do n = n + 1 end return n end)()"), 3e6);
}

TEST(LuaStateTest, CallsReportErrorsWithATraceback) {
  LuaState lua;
  const std::string error = RunLua(lua, "local function f()\n  error('boom')\nend\nf()", "@script.lua");
  EXPECT_THAT(error, StartsWith("script.lua:2: boom\nstack traceback:"));
  EXPECT_THAT(error, HasSubstr("script.lua:4: in main chunk"));
  EXPECT_THAT(RunLua(lua, "x = = 1", "@script.lua"), StartsWith("script.lua:1: unexpected symbol near '='"));
  // error objects that are not strings
  EXPECT_THAT(RunLua(lua, "error({})"), StartsWith("(error object is a table value)\nstack traceback:"));
  EXPECT_THAT(RunLua(lua, "error(setmetatable({}, {__tostring = function() return 'custom' end}))"),
              StartsWith("custom"));
  // results are left on the stack; failures leave nothing
  lua_State* L = lua.get();
  lua_getglobal(L, "max");
  lua_pushnumber(L, 1);
  lua_pushnumber(L, 5);
  std::string message;
  ASSERT_TRUE(lua.Call(2, 1, &message));
  EXPECT_EQ(lua_tonumber(L, -1), 5.0);
  lua_pop(L, 1);
  lua_getglobal(L, "error");
  lua_pushstring(L, "failed");
  EXPECT_FALSE(lua.Call(1, 1, &message));
  EXPECT_THAT(message, StartsWith("failed\nstack traceback:"));
  EXPECT_EQ(lua_gettop(L), 0);
}

}  // namespace
}  // namespace mechflow::scripting
