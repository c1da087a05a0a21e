#pragma once
// CompiledExpression: a Lua expression compiled once into a function of named
// arguments, then evaluated many times inside a right-hand side.
//
// The expression becomes
//   local sin, m, c = ...            -- only the names it uses
//   return function(t, N, v) return (EXPR) end
// so identifiers and built-in functions are upvalues and arguments are locals:
// evaluating it parses nothing and looks no global name up. Identifier names
// are case-insensitive (rewritten to their canonical lower-case form); their
// values are fixed at compilation.

#include <string>
#include <vector>

namespace mechflow::scripting {

class IdentifierTable;
class LuaState;

class CompiledExpression {
 public:
  // `chunk_name` names the expression in messages, e.g. "=block 'f'" gives
  // "block 'f':1: ...". A syntax error throws InputError.
  CompiledExpression(LuaState& lua, const std::string& expression, std::vector<std::string> argument_names,
                     const IdentifierTable& identifiers, const std::string& chunk_name);
  ~CompiledExpression();
  CompiledExpression(const CompiledExpression&) = delete;
  CompiledExpression& operator=(const CompiledExpression&) = delete;

  int num_arguments() const { return static_cast<int>(arguments_.size()); }
  const std::string& expression() const { return expression_; }

  // Evaluates with `args` in declared order. A Lua error or a result that is
  // not a finite number throws SimulationError.
  double Evaluate(const double* args) const;

 private:
  LuaState& lua_;
  std::string expression_;
  std::string label_;  // chunk name without the leading '='
  std::vector<std::string> arguments_;
  int function_ref_ = -1;  // registry reference
};

}  // namespace mechflow::scripting
