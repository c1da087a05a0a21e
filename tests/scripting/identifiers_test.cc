// IdentifierTable: ELEMENTS.md 1.1 (ordered, case-insensitive named parameters
// defined by numbers or by expressions of the identifiers above them).

#include "scripting/identifiers.h"

#include <string>
#include <utility>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <lua.hpp>

#include "mech/errors.h"
#include "scripting/lua_state.h"
#include "tests/test_util.h"

namespace mechflow::scripting {
namespace {

using mechflow::testing::InputErrorOf;
using ::testing::HasSubstr;
using ::testing::StartsWith;

// The ElastFriction list of Test ID-1.
IdentifierTable ElastFriction() {
  IdentifierTable ids;
  ids.Add("mbody", "10", "f.xml:1", "box mass", "kg");
  ids.Add("k", "50", "f.xml:2");
  ids.Add("beta", "0.1", "f.xml:3");
  ids.Add("c", "mbody*k^2*4*pi^2", "f.xml:4", "spring stiffness", "N/m");
  ids.Add("d", "2*beta*sqrt(mbody*c)", "f.xml:5");
  return ids;
}

// The message of evaluating identifiers `defs` (origins d.xml:1, d.xml:2, ...).
std::string EvaluationError(LuaState& lua, const std::vector<std::pair<std::string, std::string>>& defs) {
  return InputErrorOf([&] {
    IdentifierTable ids;
    int line = 1;
    for (const auto& [name, value] : defs) ids.Add(name, value, "d.xml:" + std::to_string(line++));
    ids.Evaluate(lua);
  });
}

// ELEMENTS.md Test ID-1.
TEST(IdentifierTableTest, ElastFrictionListEvaluatesAndFollowsOverrides) {
  LuaState lua;
  IdentifierTable ids = ElastFriction();
  ids.Evaluate(lua);
  // c = 10 * 2500 * 4 pi^2 = 986960.440...; d = 0.2 sqrt(10 c) = 628.318530...
  EXPECT_NEAR(ids.Value("c"), 986960.44, 0.01);
  EXPECT_NEAR(ids.Value("d"), 628.31853, 1e-5);

  ids.Override("K", 25);  // case-insensitive
  ids.Evaluate(lua);
  EXPECT_EQ(ids.Value("k"), 25.0);
  EXPECT_NEAR(ids.Value("c"), 246740.11, 0.01);
  EXPECT_NEAR(ids.Value("d"), 314.159, 1e-3);
  EXPECT_TRUE(ids.is_overridden(1));
  EXPECT_FALSE(ids.is_overridden(0));

  // assigning a derived identifier is refused
  EXPECT_EQ(InputErrorOf([&] { ids.Override("c", 1); }),
            "identifier 'c' is defined by an expression (c = mbody*k^2*4*pi^2, at f.xml:4); "
            "set the identifiers it depends on instead");
  EXPECT_EQ(InputErrorOf([&] { ids.Override("bta", 1); }),
            "no identifier named 'bta' (did you mean 'beta'?); identifiers: mbody, k, beta, c, d");
  EXPECT_THAT(InputErrorOf([&] { ids.Override("k", NAN); }), StartsWith("identifier 'k' cannot be set to "));
  EXPECT_EQ(InputErrorOf([&] { IdentifierTable().Override("k", 1); }),
            "no identifier named 'k'; the diagram defines none");
}

TEST(IdentifierTableTest, KeepsOrderDefinitionsAndDescriptions) {
  LuaState lua;
  IdentifierTable ids = ElastFriction();
  ids.Evaluate(lua);
  ASSERT_EQ(ids.size(), 5);
  EXPECT_EQ(ids.Names(), (std::vector<std::string>{"mbody", "k", "beta", "c", "d"}));
  EXPECT_EQ(ids.name(3), "c");
  EXPECT_EQ(ids.definition(3), "mbody*k^2*4*pi^2");
  EXPECT_TRUE(ids.is_expression(3));
  EXPECT_FALSE(ids.is_expression(0));
  EXPECT_EQ(ids.value(0), 10.0);
  EXPECT_EQ(ids.comment(0), "box mass");
  EXPECT_EQ(ids.unit(3), "N/m");
  EXPECT_EQ(ids.origin(4), "f.xml:5");
  EXPECT_EQ(ids.Find("D"), 4);
  EXPECT_EQ(ids.Find("e"), -1);
  EXPECT_FALSE(ids.Has("e"));
  EXPECT_THROW(ids.Value("e"), std::out_of_range);
}

TEST(IdentifierTableTest, NamesAreCaseInsensitive) {
  LuaState lua;
  IdentifierTable ids;
  ids.Add("Mass", "2", "f:1");
  ids.Add("W", "mass * MASS + Mass", "f:2");
  ids.Evaluate(lua);
  EXPECT_EQ(ids.Value("w"), 6.0);
  EXPECT_EQ(ids.Value("MASS"), 2.0);
  EXPECT_EQ(ids.name(0), "mass");  // stored lower-case
  EXPECT_EQ(InputErrorOf([&] { ids.Add("MASS", "1", "f:3"); }),
            "f:3: identifier 'MASS' is defined twice (first at f:1; names are case-insensitive)");
}

TEST(IdentifierTableTest, NumbersAreWholeNumbersOnly) {
  IdentifierTable ids;
  ids.Add("a", " 9.8696044E+5 ", "f:1");
  ids.Add("b", "+4", "f:2");
  ids.Add("c", "1.5abc", "f:3");
  ids.Add("d", "0x10", "f:4");
  EXPECT_FALSE(ids.is_expression(0));
  EXPECT_EQ(ids.value(0), 986960.44);
  EXPECT_FALSE(ids.is_expression(1));
  EXPECT_EQ(ids.value(1), 4.0);
  EXPECT_TRUE(ids.is_expression(2));  // and then fails to evaluate, see below
  EXPECT_TRUE(ids.is_expression(3));  // Lua reads it (16), but --set cannot
  double value = 0.0;
  EXPECT_TRUE(ParseNumber("-2e3", &value));
  EXPECT_EQ(value, -2000.0);
  for (const char* text : {"", " ", "1.5abc", "1,5", "inf", "nan", "1e999", "--1", "2*3"})
    EXPECT_FALSE(ParseNumber(text, &value)) << text;
}

TEST(IdentifierTableTest, UsingAnIdentifierBelowIsAnError) {
  LuaState lua;
  EXPECT_EQ(EvaluationError(lua, {{"a", "b + 1"}, {"b", "2"}}),
            "d.xml:1: identifier 'a': uses 'b', which is defined below it (at d.xml:2); "
            "an identifier may only use identifiers above it");
  // a cycle is always a use of something below
  EXPECT_EQ(EvaluationError(lua, {{"c", "2*D"}, {"d", "c/2"}}),
            "d.xml:1: identifier 'c': uses 'D', which is defined below it (at d.xml:2); "
            "an identifier may only use identifiers above it");
  EXPECT_EQ(EvaluationError(lua, {{"a", "a + 1"}}),
            "d.xml:1: identifier 'a': uses itself; an identifier may only use identifiers above it");
}

TEST(IdentifierTableTest, UnknownNamesGetASuggestion) {
  LuaState lua;
  EXPECT_EQ(EvaluationError(lua, {{"alpha", "1"}, {"b", "alpah * 2"}}),
            "d.xml:2: identifier 'b': unknown name 'alpah' (did you mean 'alpha'?)");
  EXPECT_EQ(EvaluationError(lua, {{"a", "sqrtt(2)"}}),
            "d.xml:1: identifier 'a': unknown name 'sqrtt' (did you mean 'sqrt'?)");
  EXPECT_EQ(EvaluationError(lua, {{"a", "Sin(2)"}}), "d.xml:1: identifier 'a': unknown name 'Sin' (did you mean 'sin'?)");
  EXPECT_EQ(EvaluationError(lua, {{"a", "2*t"}}),
            "d.xml:1: identifier 'a': unknown name 't' (t, x and v have values only while the model runs; "
            "identifiers and parameters are evaluated once, when the diagram is loaded)");
}

TEST(IdentifierTableTest, BadExpressionsReportLuasMessage) {
  LuaState lua;
  EXPECT_EQ(EvaluationError(lua, {{"a", "2 *"}}),
            "d.xml:1: identifier 'a': '2 *' is not a valid expression: unexpected symbol near <eof>");
  EXPECT_EQ(EvaluationError(lua, {{"a", "1.5abc"}}),
            "d.xml:1: identifier 'a': '1.5abc' is not a valid expression: malformed number near '1.5abc'");
  EXPECT_EQ(EvaluationError(lua, {{"a", "1; os.exit()"}}),
            "d.xml:1: identifier 'a': '1; os.exit()' is not a valid expression: <eof> expected near 'os'");
  EXPECT_EQ(EvaluationError(lua, {{"a", "error('too small')"}}),
            "d.xml:1: identifier 'a': error evaluating 'error('too small')': too small");
  EXPECT_EQ(EvaluationError(lua, {{"a", "'x' + 1"}}),
            "d.xml:1: identifier 'a': error evaluating ''x' + 1': attempt to add a 'string' with a 'number'");
  EXPECT_EQ(EvaluationError(lua, {{"a", "'text'"}}),
            "d.xml:1: identifier 'a': ''text'' does not give a number (it gives a string)");
  EXPECT_EQ(EvaluationError(lua, {{"a", "1 < 2"}}),
            "d.xml:1: identifier 'a': '1 < 2' does not give a number (it gives a boolean); "
            "write 'cond and 1 or 0' for a number");
  EXPECT_EQ(EvaluationError(lua, {{"a", "1, 2"}}), "d.xml:1: identifier 'a': '1, 2' gives 2 values; expected one number");
  EXPECT_EQ(EvaluationError(lua, {{"a", "1/0"}}), "d.xml:1: identifier 'a': '1/0' gives inf");
  EXPECT_THAT(EvaluationError(lua, {{"a", "0/0"}}), HasSubstr("'0/0' gives "));
  // what it was given: the identifiers it names, once each (a number's digits name none)
  EXPECT_THAT(EvaluationError(lua, {{"k", "800"}, {"m", "-2"}, {"wn", "math.sqrt(k/m) + 2e3 * m / M"}}),
              ::testing::EndsWith("' gives -nan (with k = 800, m = -2 in SI)"));
  EXPECT_THAT(EvaluationError(lua, {{"a", "(function() while true do end end)()"}}),
              StartsWith("d.xml:1: identifier 'a': error evaluating '(function() while true do end end)()': "
                         "instruction limit exceeded"));
  // the state is fine afterwards, without the count hook left behind
  EXPECT_EQ(lua_gethook(lua.get()), nullptr);
  std::string error;
  EXPECT_TRUE(lua.Run("local n = 0 for i = 1, 1e6 do n = n + 1 end", "=after", &error)) << error;
  EXPECT_EQ(lua_gettop(lua.get()), 0);
}

TEST(IdentifierTableTest, NamesMustBeUsableInExpressions) {
  IdentifierTable ids;
  auto add = [&](const std::string& name, const std::string& value = "1") {
    return InputErrorOf([&] { ids.Add(name, value, "f:1"); });
  };
  EXPECT_EQ(add("2x"), "f:1: identifier name '2x' must start with a letter or '_' and contain only letters, digits and '_'");
  EXPECT_THAT(add("a-b"), HasSubstr("must start with a letter"));
  EXPECT_THAT(add(""), HasSubstr("must start with a letter"));
  EXPECT_EQ(add("End"), "f:1: identifier name 'End' is reserved (a Lua keyword); choose another name");
  EXPECT_EQ(add("t"), "f:1: identifier name 't' is reserved (t is time, x and v are force-law arguments); choose another name");
  EXPECT_THAT(add("X"), HasSubstr("is reserved (t is time"));
  EXPECT_THAT(add("v"), HasSubstr("is reserved (t is time"));
  EXPECT_EQ(add("sin"), "f:1: identifier name 'sin' is reserved (a built-in function or constant); choose another name");
  EXPECT_THAT(add("PI"), HasSubstr("is reserved (a built-in function or constant)"));
  EXPECT_THAT(add("tanh"), HasSubstr("is reserved (a built-in function or constant)"));
  EXPECT_EQ(add("Math"), "f:1: identifier name 'Math' is reserved (a Lua function or library); choose another name");
  EXPECT_THAT(add("error"), HasSubstr("is reserved (a Lua function or library)"));
  EXPECT_EQ(add("a", "  "), "f:1: identifier 'a' has an empty value");
  EXPECT_EQ(ids.size(), 0);
  EXPECT_EQ(add("_x1"), "");
  EXPECT_EQ(add("T_end"), "");
}

TEST(IdentifierTableTest, ExpressionsOverAllIdentifiers) {
  LuaState lua;
  IdentifierTable ids;
  ids.Add("m", "2", "f:1");
  ids.Add("c", "8*m", "f:2");
  ids.Evaluate(lua);
  EXPECT_EQ(ids.EvaluateExpression(lua, "-c/M", "file.xml:12: block 'k' parameter 'k'"), -8.0);
  EXPECT_EQ(ids.EvaluateExpression(lua, "sqrt(C*m/2) + math.floor(2.5) + max(1, 2)", "w"), 8.0);
  EXPECT_EQ(InputErrorOf([&] { ids.EvaluateExpression(lua, "-cc/m", "file.xml:12: block 'k' parameter 'k'"); }),
            "file.xml:12: block 'k' parameter 'k': unknown name 'cc' (did you mean 'c'?)");
  EXPECT_EQ(InputErrorOf([&] { ids.EvaluateExpression(lua, "-c/", "file.xml:12: block 'k' parameter 'k'"); }),
            "file.xml:12: block 'k' parameter 'k': '-c/' is not a valid expression: unexpected symbol near <eof>");
  EXPECT_EQ(lua_gettop(lua.get()), 0);
}

// Lua's compiler takes time growing with the square of the number of
// 'and'/'or' in one chunk (a million: about half an hour): an identifier's
// expression that long is refused before it is compiled.
TEST(IdentifierTableTest, ExpressionsLuaWouldCompileForMinutesAreRefused) {
  LuaState lua;
  std::string chain = "1";
  for (int i = 0; i < 100000; ++i) chain += " and 1";
  const std::string message = EvaluationError(lua, {{"p", chain}});
  EXPECT_THAT(message, StartsWith("d.xml:1"));
  EXPECT_THAT(message, HasSubstr("'and'/'or'"));
}

}  // namespace
}  // namespace mechflow::scripting
