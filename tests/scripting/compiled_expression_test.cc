// CompiledExpression: compiled once, evaluated many times with no parsing, no
// name look-up and no allocation.

#include "scripting/compiled_expression.h"
#include "scripting/identifier_bindings.h"

#include <cmath>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <lua.hpp>

#include "mech/errors.h"
#include "scripting/identifiers.h"
#include "scripting/lua_state.h"
#include "tests/test_util.h"

namespace mechflow::scripting {
namespace {

using mechflow::testing::InputErrorOf;
using ::testing::HasSubstr;
using ::testing::StartsWith;

// The message of the SimulationError `f` throws, or "".
template <typename F>
std::string SimulationErrorOf(F&& f) {
  try {
    f();
  } catch (const SimulationError& e) {
    return e.what();
  }
  return "";
}

class CompiledExpressionTest : public ::testing::Test {
 protected:
  CompiledExpressionTest() {
    ids_.Add("Mu", "0.5", "f:1");
    ids_.Add("Mass", "2", "f:2");
    ids_.Add("eps", "1e-3", "f:3");
    ids_.Evaluate(lua_);
  }
  LuaState lua_;
  IdentifierTable ids_;
};

TEST_F(CompiledExpressionTest, EvaluatesArgumentsAndIdentifiersManyTimes) {
  CompiledExpression e(lua_, "MU * N * tanh(v / EPS) + t", {"t", "N", "v"}, ids_, "=block 'f'");
  EXPECT_EQ(e.num_arguments(), 3);
  EXPECT_EQ(e.argument_name(1), "N");
  EXPECT_EQ(e.label(), "block 'f'");
  EXPECT_EQ(e.identifiers_used(), (std::vector<std::string>{"mu", "eps"}));
  // the Lua function computes exactly what C++ does: same operations, same order
  for (int i = 0; i < 100000; ++i) {
    const double args[] = {0.1 * (i % 7), 10.0 + i % 3, 1e-3 * ((i % 5) - 2)};
    ASSERT_EQ(e.Evaluate(args), 0.5 * args[1] * std::tanh(args[2] / 1e-3) + args[0]) << i;
  }
  EXPECT_EQ(lua_gettop(lua_.get()), 0) << "the Lua stack stays balanced";
}

TEST_F(CompiledExpressionTest, EvaluatingAllocatesNothingInLua) {
  CompiledExpression e(lua_, "mass * sqr(u) + sin(t)", {"t", "u"}, ids_, "=f");
  lua_State* L = lua_.get();
  lua_gc(L, LUA_GCCOLLECT);
  lua_gc(L, LUA_GCSTOP);  // so garbage made in the loop would show as growth
  const double first[] = {0.25, 3.0};
  (void)e.Evaluate(first);  // the first call may size Lua's call stack
  const std::size_t before = lua_.memory_in_use();
  for (int i = 0; i < 10000; ++i) {
    const double args[] = {1e-3 * i, 1.0 + i};
    (void)e.Evaluate(args);
  }
  EXPECT_EQ(lua_.memory_in_use(), before);
  lua_gc(L, LUA_GCRESTART);
}

TEST_F(CompiledExpressionTest, OnlyCodeIsRewritten) {
  const double u = 3.0;
  // strings, fields (also after '..'), table keys and comments keep their case
  EXPECT_EQ(CompiledExpression(lua_, "#'Mass' + MASS + math.pi - pi", {"u"}, ids_, "=a").Evaluate(&u), 6.0);
  EXPECT_EQ(CompiledExpression(lua_, "tonumber('1' .. Mass) + #[[Mass]]", {"u"}, ids_, "=b").Evaluate(&u), 16.0);
  EXPECT_EQ(CompiledExpression(lua_, "({Mass = 5}).Mass * MASS", {"u"}, ids_, "=c").Evaluate(&u), 10.0);
  EXPECT_EQ(CompiledExpression(lua_, "u --[[ Mass ]] * mass -- MASS", {"u"}, ids_, "=d").Evaluate(&u), 6.0);
  EXPECT_EQ(CompiledExpression(lua_, "0x1p4 + 1e+2 + .5 + u", {"u"}, ids_, "=e").Evaluate(&u), 119.5);
  EXPECT_EQ(CompiledExpression(lua_, "u == Mass + 1 and 1 or 0", {"u"}, ids_, "=f").Evaluate(&u), 1.0);
  // an expression may define a function with its own locals
  EXPECT_EQ(CompiledExpression(lua_, "(function(n) local s = 0 for i = 1, n do s = s + i * MASS end return s end)(u)",
                               {"u"}, ids_, "=g")
                .Evaluate(&u),
            12.0);
}

TEST_F(CompiledExpressionTest, UsesGlobalsAsTheyAreAtCompilation) {
  std::string error;
  ASSERT_TRUE(lua_.Run("function double(x) return 2 * x end", "@script.lua", &error)) << error;
  CompiledExpression e(lua_, "double(u) + mass", {"u"}, ids_, "=block 'f'");
  ASSERT_TRUE(lua_.Run("double = nil", "@script.lua", &error)) << error;
  const double u = 4.0;
  EXPECT_EQ(e.Evaluate(&u), 10.0);
}

TEST_F(CompiledExpressionTest, RebindIdentifiersTakesNewValues) {
  IdentifierTable ids;
  ids.Add("k", "2", "f:1");
  ids.Add("k2", "k^2", "f:2");
  ids.Evaluate(lua_);
  CompiledExpression e(lua_, "K * u + k2", {"u"}, ids, "=f");
  const double u = 10.0;
  EXPECT_EQ(e.Evaluate(&u), 24.0);
  ids.Override("k", 3);
  ids.Evaluate(lua_);
  EXPECT_EQ(e.Evaluate(&u), 24.0);  // values are taken at compilation...
  // ...and on request: k and k2 changed; `u` is an argument, not an upvalue
  EXPECT_EQ(RebindIdentifiers(lua_.get(), ids, {"k", "k2"}), 2);
  EXPECT_EQ(e.Evaluate(&u), 39.0);
  EXPECT_EQ(lua_gettop(lua_.get()), 0);
}

TEST_F(CompiledExpressionTest, RebindReachesOnlyLiveExpressionsUsingTheChangedNames) {
  IdentifierTable ids;
  ids.Add("a", "1", "f:1");
  ids.Add("b", "2", "f:2");
  ids.Evaluate(lua_);
  CompiledExpression uses_a(lua_, "a", {}, ids, "=f");
  { CompiledExpression gone(lua_, "a + 1", {}, ids, "=g"); }
  CompiledExpression uses_b(lua_, "b", {}, ids, "=h");
  lua_gc(lua_.get(), LUA_GCCOLLECT);  // the destroyed expression's function is collected
  ids.Override("a", 5);
  ids.Evaluate(lua_);
  EXPECT_EQ(RebindIdentifiers(lua_.get(), ids, {"a"}), 1);
  EXPECT_EQ(uses_a.Evaluate(nullptr), 5.0);
  EXPECT_EQ(uses_b.Evaluate(nullptr), 2.0);
}

TEST_F(CompiledExpressionTest, CompileErrorsNameTheExpressionAndChunk) {
  EXPECT_EQ(InputErrorOf([&] { CompiledExpression(lua_, "u *", {"u"}, ids_, "=block 'f'"); }),
            "expression 'u *' does not compile: block 'f':1: unexpected symbol near <eof>");
  EXPECT_EQ(InputErrorOf([&] { CompiledExpression(lua_, "u +* 2", {"u"}, ids_, "=block 'f'"); }),
            "expression 'u +* 2' does not compile: block 'f':1: unexpected symbol near '*'");
  EXPECT_EQ(InputErrorOf([&] { CompiledExpression(lua_, "u, 1", {"u"}, ids_, "=block 'f'"); }),
            "expression 'u, 1' does not compile as one expression: block 'f':1: ')' expected near ','");
  EXPECT_EQ(InputErrorOf([&] { CompiledExpression(lua_, "u) end; os.exit(", {"u"}, ids_, "=block 'f'"); }),
            "expression 'u) end; os.exit(' does not compile: block 'f':1: <eof> expected near ')'");
  EXPECT_EQ(InputErrorOf([&] { CompiledExpression(lua_, "mas * u", {"u"}, ids_, "=block 'f'"); }),
            "expression 'mas * u' uses the unknown name 'mas' (did you mean 'mass'?); its arguments are u");
  EXPECT_EQ(InputErrorOf([&] { CompiledExpression(lua_, "sin(t)", {}, ids_, "=block 'f'"); }),
            "expression 'sin(t)' uses the unknown name 't'; it has no arguments");
  EXPECT_EQ(InputErrorOf([&] { CompiledExpression(lua_, "u", {"u", "u"}, ids_, "=block 'f'"); }),
            "block 'f': argument name 'u' is given twice");
  EXPECT_EQ(InputErrorOf([&] { CompiledExpression(lua_, "u", {"end"}, ids_, "=block 'f'"); }),
            "block 'f': argument name 'end' is not a Lua name");
  EXPECT_EQ(InputErrorOf([&] { CompiledExpression(lua_, "MASS", {"MASS"}, ids_, "=block 'f'"); }),
            "block 'f': argument name 'MASS' is also the name of the identifier 'Mass' (f:2); rename one of them");
  EXPECT_EQ(lua_gettop(lua_.get()), 0);
}

TEST_F(CompiledExpressionTest, RunTimeErrorsAreSimulationErrors) {
  CompiledExpression failing(lua_, "u > 1 and error('too big') or u", {"t", "u"}, ids_, "=block 'g'");
  const double small[] = {0.0, 0.5}, big[] = {1.5, 2.0};
  EXPECT_EQ(failing.Evaluate(small), 0.5);
  EXPECT_EQ(SimulationErrorOf([&] { failing.Evaluate(big); }),
            "block 'g': expression error at t = 1.5, u = 2: block 'g':1: too big");
  EXPECT_EQ(failing.Evaluate(small), 0.5);  // and it keeps working

  const double u = -1.0;
  EXPECT_EQ(SimulationErrorOf([&] { CompiledExpression(lua_, "u .. 'x'", {"u"}, ids_, "=h").Evaluate(&u); }),
            "h: expression 'u .. 'x'' gives a string, not a number, at u = -1");
  EXPECT_EQ(SimulationErrorOf([&] { CompiledExpression(lua_, "u < 0", {"u"}, ids_, "=h").Evaluate(&u); }),
            "h: expression 'u < 0' gives a boolean, not a number, at u = -1 (write 'cond and 1 or 0' for a number)");
  EXPECT_THAT(SimulationErrorOf([&] { CompiledExpression(lua_, "sqrt(u)", {"u"}, ids_, "=h").Evaluate(&u); }),
              AllOf(StartsWith("h: expression 'sqrt(u)' gives "), HasSubstr("nan at u = -1")));
  EXPECT_EQ(SimulationErrorOf([&] { CompiledExpression(lua_, "1/(u + 1)", {"u"}, ids_, "=h").Evaluate(&u); }),
            "h: expression '1/(u + 1)' gives inf at u = -1");
  EXPECT_EQ(SimulationErrorOf([&] { CompiledExpression(lua_, "error({})", {}, ids_, "=h").Evaluate(nullptr); }),
            "h: expression error: (error object is a table value)");
  EXPECT_EQ(lua_gettop(lua_.get()), 0);
}

TEST_F(CompiledExpressionTest, ErrorsInScriptFunctionsCarryATraceback) {
  std::string error;
  ASSERT_TRUE(lua_.Run("function check(x)\n  if x > 1 then error('too big') end\n  return x\nend", "@control.lua",
                       &error))
      << error;
  CompiledExpression e(lua_, "check(u)", {"u"}, ids_, "=block 'f'");
  const double u = 2.0;
  const std::string message = SimulationErrorOf([&] { e.Evaluate(&u); });
  EXPECT_THAT(message, StartsWith("block 'f': expression error at u = 2: control.lua:2: too big\nstack traceback:"));
  EXPECT_THAT(message, HasSubstr("block 'f':1: in function"));
}

}  // namespace
}  // namespace mechflow::scripting
