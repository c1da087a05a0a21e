#pragma once
// LuaScalarFunction: a compiled Lua expression seen by the mechanics as a
// mech::ScalarFunction (force laws, parameters that follow mechanism inputs).
// The argument names fix the order of the values Evaluate receives.

#include <string>
#include <vector>

#include "mech/time_function.h"
#include "scripting/compiled_expression.h"

namespace mechflow::scripting {

class LuaScalarFunction final : public mech::ScalarFunction {
 public:
  LuaScalarFunction(LuaState& lua, const std::string& expression, std::vector<std::string> argument_names,
                    const IdentifierTable& identifiers, const std::string& chunk_name)
      : expression_(lua, expression, std::move(argument_names), identifiers, chunk_name) {}
  double Evaluate(std::span<const double> args) const override { return expression_.Evaluate(args.data()); }

 private:
  CompiledExpression expression_;
};

}  // namespace mechflow::scripting
