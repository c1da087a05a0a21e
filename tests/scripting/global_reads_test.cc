// The globals a chunk reads and never defines (scripting/global_reads.h).

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "scripting/global_reads.h"
#include "scripting/identifiers.h"
#include "scripting/lua_state.h"

namespace mechflow::scripting {
namespace {

std::vector<std::string> Names(const std::vector<GlobalRead>& reads) {
  std::vector<std::string> names;
  for (const GlobalRead& r : reads) names.push_back(r.name + ":" + std::to_string(r.line));
  return names;
}

TEST(GlobalReadsTest, LocalsParametersFieldsKeysAndAssignmentsAreNotReads) {
  const std::string code =
      "local kp, kd <const> = 1, 2\n"        // 1
      "function init(sim)\n"                  // 2: init defined, sim a parameter
      "  gain = kp * sim:get('phi')\n"        // 3: gain assigned; get a method
      "  local t = { speed = 3, [1] = x0 }\n" // 4: speed a key; x0 read
      "  for i, v in ipairs(t) do y = v + i + math.pi end\n"  // 5: ipairs, math read
      "  if gain == kd then return misspelt end\n"           // 6: misspelt read
      "  ::again:: goto again\n"              // 7: a label
      "end\n"
      "function M.f(a) return a + gain end\n";  // 9: M read
  EXPECT_EQ(Names(GlobalReads(code)),
            (std::vector<std::string>{"x0:4", "ipairs:5", "math:5", "misspelt:6", "M:9"}));
}

TEST(GlobalReadsTest, UnknownAreThoseNoIdentifierOrSandboxGlobalExplains) {
  LuaState lua;
  IdentifierTable ids;
  ids.Add("X0", "1", "d.xml:1");
  ids.Evaluate(lua);
  const auto unknown = UnknownGlobals("return x0 + sqrt(math.pi) + ipairs + Kp + io", ids, lua);
  // x0 is an identifier (any case); sqrt, math, ipairs are the sandbox's; io is
  // not (sandboxed)
  EXPECT_EQ(Names(unknown), (std::vector<std::string>{"Kp:1", "io:1"}));
}

}  // namespace
}  // namespace mechflow::scripting
