#pragma once
// CompiledExpression: a Lua expression compiled once into a function of named
// arguments, then evaluated many times inside a right-hand side.
//
// The expression `MU*N*tanh(v/1e-3)` with arguments (t, N, v) becomes the chunk
//   local tanh, mu = ...; return function(t, N, v) return (MU*N*tanh(v/1e-3)) end
// with `MU` rewritten to the identifier's canonical name `mu`. Every free name
// is resolved once, at compilation:
//   1. an argument (exact case) stays a parameter of the function;
//   2. an identifier (case-insensitive) becomes an upvalue holding its value;
//   3. a global that exists now (sin, sqrt, pi, math, error, a function a
//      script defined, ...) becomes an upvalue holding that global's value;
//   4. anything else is an InputError ("unknown name 'mas' (did you mean
//      'mass'?)") -- unless the expression defines a function, whose locals
//      this resolver does not track; such names stay global look-ups.
// So evaluating parses nothing, looks no global name up and allocates nothing
// beyond Lua's own stack. Strings, comments, field names (after '.' or ':')
// and table-constructor keys are left alone. The expression stays on line 1,
// so Lua's messages point at it ("block 'f':1: ...").
//
// Identifier values are taken at compilation; the function is registered with
// BindIdentifiers (scripting/identifier_bindings.h), so RebindIdentifiers
// gives it new values when a control script changes identifiers.
//
// Evaluation is bounded by the LuaState's instruction limit, except for
// straight-line expressions, which cannot loop and so skip the count hook (a
// hook call per VM instruction, measured +40% per evaluation): no `function`,
// no string, bracket or method call, and every global used is a number or
// one of the sandbox's functions of numbers (LuaState::IsPureFunction; sin,
// sqrt, ...). Then no value the expression reaches has a metatable through
// which Lua code could run, and no function it calls runs any: a table of a
// script, any other C function (pcall, or load with a reader) or a sandbox
// name a script rebound makes the expression bounded. Upvalues are fixed at
// compilation, so this cannot change later.
//
// The LuaState must outlive the expression.

#include <string>
#include <vector>

namespace mechflow::scripting {

class IdentifierTable;
class LuaState;

class CompiledExpression {
 public:
  // `argument_names` are Lua names in the order Evaluate takes them.
  // `chunk_name` names the expression in messages: "=block 'f'" gives
  // "block 'f':1: ...". A syntax error or an unknown name throws InputError.
  CompiledExpression(LuaState& lua, const std::string& expression, std::vector<std::string> argument_names,
                     const IdentifierTable& identifiers, const std::string& chunk_name);
  ~CompiledExpression();
  CompiledExpression(const CompiledExpression&) = delete;
  CompiledExpression& operator=(const CompiledExpression&) = delete;

  int num_arguments() const { return static_cast<int>(arguments_.size()); }
  const std::string& argument_name(int i) const { return arguments_.at(i); }
  const std::string& expression() const { return expression_; }
  // The chunk name without its leading '=' or '@' ("block 'f'").
  const std::string& label() const { return label_; }
  // Lower-case names of the identifiers the expression uses.
  const std::vector<std::string>& identifiers_used() const { return identifiers_used_; }

  // Evaluates with `args[i]` for argument i. A Lua error, or a result that is
  // not a finite number, throws SimulationError:
  //   "block 'f': expression error at t = 0.5, u = 2: block 'f':1: too big".
  double Evaluate(const double* args) const;

 private:
  // "at t = 0.5, u = 2" for messages ("" without arguments).
  std::string DescribeArguments(const double* args) const;

  LuaState& lua_;
  std::string expression_;
  std::string label_;
  std::vector<std::string> arguments_;
  std::vector<std::string> identifiers_used_;
  // false when the expression is straight-line code that cannot loop: then it
  // runs without the instruction count, whose hook would slow every step
  bool bounded_ = true;
  int function_ref_ = -1;  // registry reference to the compiled function
  int handler_ref_ = -1;   // registry reference to its message handler
};

}  // namespace mechflow::scripting
