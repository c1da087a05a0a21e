// Fuzz target: the time-function compiler (prescribed motions), its text
// compiled against two identifiers and evaluated at a few times.

#include "scripting/identifiers.h"
#include "scripting/jet_expression.h"
#include "scripting/lua_state.h"
#include "tests/fuzz/fuzz_target.h"

namespace {

void CompileAndEvaluate(const std::string& text) {
  static mechflow::scripting::LuaState lua;
  static mechflow::scripting::IdentifierTable identifiers = [] {
    mechflow::scripting::IdentifierTable ids;
    ids.Add("omega", "6.283", "fuzz.xml:1");
    ids.Add("a", "0.5", "fuzz.xml:2");
    ids.Evaluate(lua);
    return ids;
  }();
  const mechflow::scripting::JetExpression f(text, identifiers, "fuzz");
  for (const double t : {0.0, 0.25, 1.0, -3.5, 1e6}) f.Evaluate(t);
}

}  // namespace

MECHFLOW_FUZZ_TARGET(CompileAndEvaluate)
