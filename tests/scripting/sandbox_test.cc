// The Lua sandbox, attacked the way a diagram or script from someone else
// could: files, processes, modules, bytecode, memory exhaustion and endless
// loops each fail with a clear error, and the state stays usable afterwards.
// The same code in an unsafe state shows that io and os are there.

#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <lua.hpp>

#include "mech/errors.h"
#include "scripting/compiled_expression.h"
#include "scripting/identifiers.h"
#include "scripting/lua_state.h"
#include "tests/test_util.h"

namespace mechflow::scripting::sandbox_test {  // names of its own: the files of its folder are compiled together
namespace {

using mechflow::testing::InputErrorOf;
using ::testing::HasSubstr;
using ::testing::StartsWith;

// Runs `code` as a chunk named "script.lua"; returns "" or the error message.
std::string RunScript(LuaState& lua, const std::string& code) {
  std::string error;
  return lua.Run(code, "@script.lua", &error) ? "" : error;
}

// The message of the SimulationError evaluating `e` at x = 1 throws, or "".
std::string EvaluationError(const CompiledExpression& e) {
  const double x = 1.0;
  try {
    e.Evaluate(&x);
  } catch (const SimulationError& error) {
    return error.what();
  }
  return "";
}

// The state still runs code, and the stack is balanced.
void ExpectUsable(LuaState& lua) {
  EXPECT_EQ(RunScript(lua, "assert(string.rep('ab', 3) == 'ababab' and math.sqrt(16) == 4)"), "");
  EXPECT_EQ(lua_gettop(lua.get()), 0);
}

// What a hostile chunk tries, and the error the sandbox gives.
struct Attack {
  const char* code;
  const char* error;
};
constexpr Attack kAttacks[] = {
    {"os.execute('touch /tmp/mechflow_sandbox_breached')",
     "script.lua:1: attempt to index a nil value (global 'os')"},
    {"local f = io.open('/etc/passwd')", "script.lua:1: attempt to index a nil value (global 'io')"},
    {"local m = require('os')", "script.lua:1: attempt to call a nil value (global 'require')"},
    {"package.loadlib('libc.so.6', 'system')", "script.lua:1: attempt to index a nil value (global 'package')"},
    {"debug.sethook()", "script.lua:1: attempt to index a nil value (global 'debug')"},
    {"dofile('/etc/passwd')", "script.lua:1: attempt to call a nil value (global 'dofile')"},
    {"loadfile('/etc/passwd')", "script.lua:1: attempt to call a nil value (global 'loadfile')"},
    {"assert(load(string.dump(function() return 1 end), 'dumped', 'b'))",
     "script.lua:1: attempt to load a binary chunk (mode is 't')"},
};

TEST(SandboxTest, ChunksFindNoFilesProcessesModulesOrBytecode) {
  LuaState lua;
  for (const Attack& attack : kAttacks) {
    EXPECT_THAT(RunScript(lua, attack.code), StartsWith(attack.error)) << attack.code;
    ExpectUsable(lua);
  }
}

TEST(SandboxTest, UnsafeStateHasIoAndOs) {
  LuaState lua({.unsafe = true});
  EXPECT_EQ(RunScript(lua, "assert(io.open and os.execute and os.getenv and require and package and debug)"), "");
  EXPECT_EQ(RunScript(lua, "assert(os.time() > 0)"), "");
  EXPECT_EQ(RunScript(lua, "assert(io.open('/nonexistent/mechflow') == nil)"), "");
  EXPECT_EQ(RunScript(lua, "assert(require('string') == string)"), "");
  // bytecode stays refused: it is not verified and can crash the interpreter
  EXPECT_THAT(RunScript(lua, kAttacks[7].code), StartsWith(kAttacks[7].error));
  ExpectUsable(lua);
}

TEST(SandboxTest, StringRepCannotExhaustMemory) {
  LuaState lua({.memory_limit = std::size_t(16) << 20});
  EXPECT_EQ(lua.memory_limit(), std::size_t(16) << 20);
  // one huge string, and a string doubled until it does not fit
  EXPECT_EQ(RunScript(lua, "local s = string.rep('x', 1 << 30)"), "not enough memory (Lua may use at most 16 MiB)");
  EXPECT_EQ(RunScript(lua, "local s = 'x' while true do s = s .. s end"),
            "not enough memory (Lua may use at most 16 MiB)");
  EXPECT_LE(lua.memory_in_use(), std::size_t(16) << 20);
  ExpectUsable(lua);
  // pcall does not help a script past the limit: what it holds stays counted.
  // string.rep of 1 MiB needs 2 MiB for a moment (buffer, then the string), so
  // 14 strings fit in 16 MiB with the interpreter's own few tens of kB.
  EXPECT_EQ(RunScript(lua, "held = {}\nfor i = 1, 100 do\n  local ok, s = pcall(string.rep, 'x', 1 << 20)\n"
                           "  if not ok then assert(s == 'not enough memory', s) break end\n  held[i] = s\nend"),
            "");
  EXPECT_EQ(RunScript(lua, "assert(#held == 14, #held) held = nil"), "");
  lua_gc(lua.get(), LUA_GCCOLLECT);
  EXPECT_LT(lua.memory_in_use(), std::size_t(1) << 20);  // the memory comes back
  ExpectUsable(lua);
}

TEST(SandboxTest, EndlessLoopStopsWellWithinASecond) {
  LuaState lua;  // the default limit
  const auto start = std::chrono::steady_clock::now();
  const std::string error = RunScript(lua, "local n = 0\nwhile true do n = n + 1 end");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_THAT(error, StartsWith("script.lua:2: instruction limit exceeded (10000000 instructions in one call; "
                                "endless loop?)\nstack traceback:"));
  EXPECT_LT(seconds, 1.0);  // 0.05 to 0.2 s measured on a loaded machine
  std::printf("[ measured ] 'while true' stopped after %.3f s\n", seconds);
  ExpectUsable(lua);
}

// Expressions (identifiers, expression blocks) go through the same state.
class SandboxExpressionTest : public ::testing::Test {
 protected:
  SandboxExpressionTest() { ids_.Evaluate(lua_); }
  CompiledExpression Compile(const std::string& expression) {
    return CompiledExpression(lua_, expression, {"x"}, ids_, "=block 'f'");
  }
  LuaState lua_;
  IdentifierTable ids_;
};

TEST_F(SandboxExpressionTest, UnavailableLibrariesAreUnknownNames) {
  for (const char* name : {"os", "io", "require", "package", "debug", "dofile", "loadfile"}) {
    EXPECT_THAT(InputErrorOf([&] { Compile(std::string(name) + ".x"); }),
                HasSubstr(std::string("uses the unknown name '") + name + "'"))
        << name;
  }
  ExpectUsable(lua_);
}

TEST_F(SandboxExpressionTest, RuntimeAttacksFailWithTheBlockNamed) {
  // a function in the expression keeps global look-ups, so these fail at run time
  EXPECT_THAT(EvaluationError(Compile("(function() return os.execute('true') end)()")),
              HasSubstr("block 'f':1: attempt to index a nil value (global 'os')"));
  EXPECT_THAT(EvaluationError(Compile("(function() return assert(load(string.dump(function() end)))() end)()")),
              HasSubstr("block 'f':1: attempt to load a binary chunk (mode is 't')"));
  ExpectUsable(lua_);
}

TEST_F(SandboxExpressionTest, EndlessLoopAndMemoryExhaustionEndTheEvaluation) {
  const CompiledExpression loop = Compile("(function() while true do end end)() or x");
  const auto start = std::chrono::steady_clock::now();
  EXPECT_THAT(EvaluationError(loop), StartsWith("block 'f': expression error at x = 1: block 'f':1: instruction "
                                                "limit exceeded (10000000 instructions in one call"));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(seconds, 1.0);  // 0.05 to 0.2 s measured on a loaded machine
  std::printf("[ measured ] endless loop in an expression stopped after %.3f s\n", seconds);

  lua_.set_memory_limit(std::size_t(32) << 20);
  const CompiledExpression hog = Compile("#string.rep('x', 1 << 30) + x");
  EXPECT_EQ(EvaluationError(hog),
            "block 'f': expression error at x = 1: not enough memory (Lua may use at most 32 MiB)");
  // the state, and a normal expression in it, still work
  const CompiledExpression fine = Compile("2 * x + #string.rep('x', 10)");
  const double x = 3.0;
  EXPECT_EQ(fine.Evaluate(&x), 16.0);
  ExpectUsable(lua_);
}

// 1 when called under the instruction count hook, else 0.
int Hooked(lua_State* L) {
  lua_pushnumber(L, lua_gethook(L) ? 1 : 0);
  return 1;
}

TEST_F(SandboxExpressionTest, OnlyExpressionsThatCanLoopAreCounted) {
  lua_register(lua_.get(), "hooked", &Hooked);
  const double x = 1.0;
  // straight-line: numbers and the sandbox's functions of numbers only, so it
  // cannot loop and is not counted (under a limit of one instruction, a
  // counted evaluation would fail)
  const CompiledExpression fast = Compile("sin(x) * pi");
  lua_.set_instruction_limit(1);
  EXPECT_EQ(fast.Evaluate(&x), std::sin(1.0) * M_PI);
  lua_.set_instruction_limit(10'000'000);
  // each of these could reach Lua code that loops, so each is counted; so is
  // a call of any other C function (hooked itself: pcall or load may run Lua)
  for (const char* expression : {"hooked() + 0 * sin(x)", "hooked() + #'ab' - 2",
                                 "hooked() + (function() return 0 end)()", "hooked() + math.abs(0)",
                                 "hooked() + ({0})[1]", "hooked() + #(''):rep(0)"})
    EXPECT_EQ(Compile(expression).Evaluate(&x), 1.0) << expression;
  EXPECT_EQ(lua_gethook(lua_.get()), nullptr);  // and the hook is gone afterwards
}

}  // namespace
}  // namespace mechflow::scripting::sandbox_test
