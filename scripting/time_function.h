#pragma once
// CompiledTimeFunction: s(t) of a prescribed motion (tt/rt transformations)
// with its first and second time derivatives computed exactly, by
// forward-mode automatic differentiation on (value, d/dt, d2/dt2) triples.
//
// Grammar (the math subset of the Lua expressions used elsewhere, ELEMENTS.md
// 1.1): numbers (1, .5, 9.8696044E+5), identifiers (case-insensitive, values
// taken at compilation), t, pi; + - * / and ^ (right-associative, binding
// tighter than unary minus: -2^2 = -4, as in Lua); parentheses; functions
// sin cos tan asin acos atan (also arcsin arccos arctan) exp ln log sqrt sqr
// abs sign min max sinh cosh tanh. Anything else (Lua operators, field
// access, unknown names) is an InputError naming where and what was expected.
//
// Compilation produces a postfix tape; Evaluate runs it on a stack sized at
// compilation, so it allocates nothing.

#include <string>
#include <vector>

#include "mech/time_function.h"

namespace mechflow::scripting {

class IdentifierTable;

class CompiledTimeFunction final : public mech::TimeFunction {
 public:
  // `what` starts every message ("model.xml:12: joint 'j' transformation 2").
  CompiledTimeFunction(const std::string& text, const IdentifierTable& identifiers, const std::string& what);

  mech::Jet Evaluate(double t) const override;
  bool depends_on_time() const { return uses_time_; }
  const std::string& text() const { return text_; }

  enum class Op { kConst, kTime, kAdd, kSub, kMul, kDiv, kPow, kNeg, kCall1, kCall2 };
  struct Instruction {
    Op op;
    double value = 0.0;  // kConst
    int function = 0;    // kCall1 / kCall2
  };

 private:
  std::string text_, what_;
  std::vector<Instruction> tape_;
  mutable std::vector<mech::Jet> stack_;  // sized at compilation
  bool uses_time_ = false;
};

}  // namespace mechflow::scripting
