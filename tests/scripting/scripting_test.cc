// The Lua sandbox, identifiers and compiled expressions.

#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <lua.hpp>

#include "mech/errors.h"
#include "scripting/compiled_expression.h"
#include "scripting/identifiers.h"
#include "scripting/lua_state.h"
#include "tests/test_util.h"

namespace mechflow::scripting {
namespace {

using ::testing::HasSubstr;
using mechflow::testing::InputErrorOf;

// Runs `code` in `lua`; returns "" or the error message.
std::string RunLua(LuaState& lua, const std::string& code) {
  lua_State* L = lua.get();
  if (luaL_loadbufferx(L, code.data(), code.size(), "=test", "t") != LUA_OK || lua_pcall(L, 0, 0, 0) != LUA_OK) {
    std::string message = lua_tostring(L, -1);
    lua_pop(L, 1);
    return message;
  }
  return "";
}

TEST(LuaStateTest, SandboxHasNoFilesProcessesOrModules) {
  LuaState lua;
  for (const char* name : {"io", "os", "require", "package", "debug", "dofile", "loadfile"})
    EXPECT_EQ(RunLua(lua, std::string("assert(") + name + " == nil)"), "") << name;
  EXPECT_THAT(RunLua(lua, "os.execute('true')"), HasSubstr("attempt to index a nil value (global 'os')"));
  // bytecode is refused even through load
  EXPECT_THAT(RunLua(lua, "local f = assert(load(string.dump(function() return 1 end)))"),
              HasSubstr("attempt to load a binary chunk"));
  EXPECT_EQ(RunLua(lua, "assert(load('return 1')() == 1)"), "");
}

TEST(LuaStateTest, UnsafeStateOpensEverything) {
  LuaState lua(/*unsafe=*/true);
  EXPECT_EQ(RunLua(lua, "assert(io and os and require)"), "");
}

TEST(LuaStateTest, ExpressionFunctionsAreDefined) {
  LuaState lua;
  EXPECT_EQ(RunLua(lua, "assert(sqr(3) == 9 and sign(-2) == -1 and ln(1) == 0 and arctan(0) == 0 "
                        "and math.abs(tanh(0.5) - 0.46211715726) < 1e-10 and tanh(100) == 1 and pi > 3.14)"),
            "");
}

TEST(LuaStateTest, MemoryAndInstructionLimitsStopRunawayCode) {
  LuaState lua;
  lua.set_memory_limit(8 << 20);
  EXPECT_THAT(RunLua(lua, "local s = string.rep('x', 64 * 1024 * 1024)"), HasSubstr("not enough memory"));
  InstructionLimit limit(lua, 1000000);
  EXPECT_THAT(RunLua(lua, "while true do end"), HasSubstr("instruction limit exceeded"));
}

// ELEMENTS.md Test ID-1 (the ElastFriction identifier list).
TEST(IdentifierTableTest, DerivedIdentifiersFollowTheirInputs) {
  auto make = [] {
    IdentifierTable ids;
    ids.Add("mbody", "10", "f:1");
    ids.Add("k", "50", "f:2");
    ids.Add("beta", "0.1", "f:3");
    ids.Add("c", "mbody*k^2*4*pi^2", "f:4");
    ids.Add("d", "2*beta*sqrt(mbody*c)", "f:5");
    return ids;
  };
  LuaState lua;
  IdentifierTable ids = make();
  ids.Evaluate(lua);
  EXPECT_NEAR(ids.Value("c"), 986960.44, 0.01);
  EXPECT_NEAR(ids.Value("d"), 628.31853, 1e-5);
  IdentifierTable changed = make();
  changed.Override("K", 25);  // case-insensitive
  changed.Evaluate(lua);
  EXPECT_NEAR(changed.Value("c"), 246740.11, 0.01);
  EXPECT_NEAR(changed.Value("d"), 314.159, 1e-3);
  EXPECT_THAT(InputErrorOf([&] { changed.Override("c", 1); }),
              HasSubstr("identifier 'c' is defined by an expression (c = mbody*k^2*4*pi^2, at f:4)"));
  EXPECT_THAT(InputErrorOf([&] { changed.Override("bta", 1); }),
              HasSubstr("no identifier named 'bta' (did you mean 'beta'?)"));
}

TEST(IdentifierTableTest, NamesAreCaseInsensitive) {
  LuaState lua;
  IdentifierTable ids;
  ids.Add("Mass", "2", "f:1");
  ids.Add("w", "mass * MASS", "f:2");
  ids.Evaluate(lua);
  EXPECT_EQ(ids.Value("W"), 4.0);
  EXPECT_THAT(InputErrorOf([&] { ids.Add("MASS", "1", "f:3"); }),
              HasSubstr("f:3: identifier 'MASS' is defined twice (first at f:1"));
}

TEST(IdentifierTableTest, ErrorsNameTheIdentifierAndItsOrigin) {
  LuaState lua;
  auto error = [&](const std::vector<std::pair<std::string, std::string>>& defs) {
    return InputErrorOf([&] {
      IdentifierTable ids;
      int line = 1;
      for (const auto& [name, value] : defs) ids.Add(name, value, "d.xml:" + std::to_string(line++));
      ids.Evaluate(lua);
    });
  };
  EXPECT_THAT(error({{"a", "b + 1"}, {"b", "2"}}),
              HasSubstr("d.xml:1: identifier 'a': uses 'b', which is defined below it (at d.xml:2)"));
  EXPECT_THAT(error({{"a", "b"}, {"b", "a"}}), HasSubstr("which is defined below it"));
  EXPECT_THAT(error({{"alpha", "1"}, {"b", "alpah * 2"}}),
              HasSubstr("d.xml:2: identifier 'b': unknown name 'alpah' (did you mean 'alpha'?)"));
  EXPECT_THAT(error({{"a", "2 *"}}), HasSubstr("d.xml:1: identifier 'a': '2 *' is not a valid expression:"));
  EXPECT_THAT(error({{"a", "1.5abc"}}), HasSubstr("is not a valid expression"));
  EXPECT_THAT(error({{"a", "'text'"}}), HasSubstr("does not give a number"));
  EXPECT_THAT(error({{"a", "1/0"}}), HasSubstr("gives inf"));
  EXPECT_THAT(error({{"sin", "1"}}), HasSubstr("identifier name 'sin' is reserved"));
  EXPECT_THAT(error({{"a", "(function() while true do end end)()"}}), HasSubstr("instruction limit exceeded"));
}

TEST(CompiledExpressionTest, EvaluatesWithArgumentsAndIdentifiers) {
  LuaState lua;
  IdentifierTable ids;
  ids.Add("Mu", "0.5", "f:1");
  ids.Evaluate(lua);
  CompiledExpression e(lua, "MU * N * tanh(v / 1e-3) + t", {"t", "N", "v"}, ids, "=block 'f'");
  for (int i = 0; i < 100000; ++i) {
    const double args[] = {0.1 * (i % 7), 10.0 + i % 3, 1e-3 * ((i % 5) - 2)};
    const double v = args[2];
    ASSERT_DOUBLE_EQ(e.Evaluate(args), 0.5 * args[1] * std::tanh(v / 1e-3) + args[0]);
  }
  EXPECT_EQ(lua_gettop(lua.get()), 0) << "the Lua stack stays balanced";
}

TEST(CompiledExpressionTest, ErrorsNameTheExpression) {
  LuaState lua;
  IdentifierTable ids;
  EXPECT_THAT(InputErrorOf([&] { CompiledExpression(lua, "u *", {"u"}, ids, "=block 'f'"); }),
              HasSubstr("block 'f':1:"));
  CompiledExpression failing(lua, "u > 1 and error('too big') or u", {"u"}, ids, "=block 'g'");
  const double small = 0.5, big = 2.0;
  EXPECT_EQ(failing.Evaluate(&small), 0.5);
  try {
    failing.Evaluate(&big);
    FAIL() << "expected a SimulationError";
  } catch (const SimulationError& e) {
    EXPECT_THAT(e.what(), HasSubstr("block 'g':1: too big"));
  }
  CompiledExpression not_number(lua, "'abc'", {}, ids, "=block 'h'");
  EXPECT_THROW(not_number.Evaluate(nullptr), SimulationError);
}

TEST(ExpressionBlockTest, IntegratedSineMatchesClosedForm) {
  const auto run = mechflow::testing::RunXml(R"xml(<diagram>
    <identifiers><identifier name="A" value="3"/></identifiers>
    <blocks>
      <block type="expression" name="f" inputs="" expr="a*sin(t)"/>
      <block type="integrator" name="x"/>
    </blocks>
    <connections><connect from="f.y" to="x.u"/></connections>
    <solver t_end="5" rtol="1e-10" atol="1e-12"/>
    <output interval="0.1"><log signal="x.y" label="x"/></output>
  </diagram>)xml");
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto t = run.Column("time"), x = run.Column("x");
  // global error of BDF at rtol 1e-10 accumulates to ~1e-8 over 5 s
  for (size_t i = 0; i < t.size(); ++i) EXPECT_NEAR(x[i], 3 * (1 - std::cos(t[i])), 1e-7);
}

}  // namespace
}  // namespace mechflow::scripting
