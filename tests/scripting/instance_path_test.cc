// Instance paths (scripting/instance_path.h) and identifiers named by them
// (the parameters of subsystem and part instances).

#include "scripting/instance_path.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mech/errors.h"
#include "scripting/identifiers.h"
#include "scripting/lua_state.h"
#include "tests/test_util.h"

namespace mechflow::scripting {
namespace {

using mechflow::testing::InputErrorOf;
using ::testing::HasSubstr;

TEST(InstancePathTest, WellFormedPathsAndTheirLuaNames) {
  EXPECT_TRUE(IsInstancePath("d[1].mu"));
  EXPECT_FALSE(IsInstancePath("mu"));
  EXPECT_EQ(InstancePathProblem("d[1].mu"), "");
  EXPECT_EQ(InstancePathProblem("chain.s[12].Box"), "");
  EXPECT_NE(InstancePathProblem("d[].mu"), "");
  EXPECT_NE(InstancePathProblem("d[x].mu"), "");
  EXPECT_NE(InstancePathProblem("d..mu"), "");
  EXPECT_NE(InstancePathProblem("d.1mu"), "");
  EXPECT_NE(InstancePathProblem("d__x.mu"), "");
  EXPECT_NE(InstancePathProblem("d.mu."), "");
  EXPECT_EQ(InstancePathLuaName("d[1].mu"), "d__1__mu");
  EXPECT_EQ(InstancePathLuaName("chain.s[12].Box"), "chain__s__12__Box");
}

TEST(InstancePathTest, TextShowsPathsForLuaNames) {
  EXPECT_EQ(WithInstancePaths("1.25*d__1__mu + chain__s__12__k^2"), "1.25*d[1].mu + chain.s[12].k^2");
  EXPECT_EQ(WithInstancePaths("m*g"), "m*g");
  EXPECT_EQ(WithInstancePaths("__index"), "__index");  // a Lua metamethod name, no path
}

TEST(InstancePathTest, IdentifiersNamedByPathsAreFoundByPathAndReadByLuaName) {
  LuaState lua;
  IdentifierTable ids;
  ids.Add("N0", "10", "d.xml:1");
  ids.Add("d[1].preload", "2*N0", "d.xml:2");
  ids.Add("d[1].mu", "0.4", "damper.xml:3");
  ids.Add("d[1].mu_s", "1.25*d__1__mu", "damper.xml:4");
  ids.Override("d[1].MU", 0.2);  // case-insensitive, as every name
  ids.Evaluate(lua);
  EXPECT_EQ(ids.Find("d[1].mu"), ids.Find("d__1__mu"));
  EXPECT_EQ(ids.spelling(2), "d[1].mu");
  EXPECT_DOUBLE_EQ(ids.Value("d[1].preload"), 20.0);
  EXPECT_DOUBLE_EQ(ids.Value("d[1].mu_s"), 0.25);
  EXPECT_THAT(InputErrorOf([&] { ids.Override("d[1].mu_s", 1.0); }),
              HasSubstr("identifier 'd[1].mu_s' is defined by an expression (d[1].mu_s = 1.25*d[1].mu"));
  EXPECT_THAT(InputErrorOf([&] { ids.Override("d[2].mu", 1.0); }), HasSubstr("did you mean 'd[1].mu'"));
}

TEST(InstancePathTest, NamesADiagramWritesMayNotLookLikeLuaNamesOfPaths) {
  IdentifierTable ids;
  EXPECT_THAT(InputErrorOf([&] { ids.Add("d__1__mu", "1", "d.xml:3"); }), HasSubstr("d.xml:3: identifier name 'd__1__mu' contains \"__\""));
  EXPECT_THAT(InputErrorOf([&] { ids.Add("d[1].x", "1", "p.xml:2"); }), HasSubstr("is reserved"));
  EXPECT_THAT(InputErrorOf([&] { ids.Add("d[a].k", "1", "p.xml:2"); }), HasSubstr("an index is written [0]"));
  ids.Add("d[0].k", "1", "p.xml:2");
  EXPECT_THAT(InputErrorOf([&] { ids.Add("D[0].K", "1", "p.xml:5"); }), HasSubstr("defined twice"));
}

}  // namespace
}  // namespace mechflow::scripting
