#pragma once
// JetExpression: an arithmetic expression of time compiled into a small
// program that returns s(t) with its first and second time derivatives (a
// mech::Jet), computed exactly by forward-mode automatic differentiation. No
// Lua and no finite differences are involved. It is what a prescribed motion
// (the tt/rt elementary transformations of a joint, ELEMENTS.md 2.1) runs.
// Compiler: scripting/jet_expression_compiler.cc; evaluator:
// scripting/jet_expression.cc; the derivative rules: scripting/jet_rules.h.
//
// Grammar (ELEMENTS.md 1.1; the arithmetic subset of the Lua expressions used
// elsewhere, with Lua's precedence):
//
//   expression := term   (('+' | '-') term)*            left-associative
//   term       := unary  (('*' | '/') unary)*           left-associative
//   unary      := ('-' | '+') unary | power
//   power      := primary ('^' unary)?                  right-associative
//   primary    := number | name | name '(' expression (',' expression)* ')'
//               | '(' expression ')'
//
//   So `^` binds tighter than unary minus (-2^2 = -4, 2^-1 = 0.5) and
//   2^3^2 = 2^9 = 512, as in Lua. Unary '+' is accepted (Lua has none).
//
//   number  decimal, with optional fraction and exponent (1, 1.5, .5, 2.,
//           9.8696044E+5), or hexadecimal as in Lua (0x1F, 0x1p-3).
//   name    t (time, s), pi, an identifier of the IdentifierTable, or a
//           function. Names are case-insensitive (ELEMENTS.md 1.1): `Omega`,
//           `OMEGA`, `T`, `PI` and `Sin` are `omega`, `t`, `pi` and `sin`.
//           (The Lua layer is stricter: there only identifiers are
//           case-insensitive, t/pi/functions must be written lower-case.)
//   functions, with their number of arguments:
//           sin cos tan sinh cosh tanh exp sqrt abs                 1
//           sqr (x*x), sign (-1, 0 or 1)                            1
//           ln, log (both the natural logarithm)                    1
//           asin acos atan, also spelt arcsin arccos arctan         1
//           atan(y, x) = arctan(y, x): the angle of (x, y), as Lua  2
//           min max                                                 2 or more
//   Lua's log(x, base) is refused (write ln(x)/ln(b)), and so are floor and
//   ceil.
//
// Identifiers are constants: their values are read from the table when the
// function is compiled and baked into the program. An identifier changed
// later (a macro variant, --set, a control script) needs a new
// JetExpression; identifiers_used() says which ones a function reads.
//
// Everything else is an InputError whose message starts with the caller's
// `what` and says what was found and what was expected: unknown names (with
// a "did you mean"), x and v (force-law arguments only), `math.sin`, Lua
// operators and keywords (.. // % == ~= < > and or not ... and `--`, which in
// Lua starts a comment), strings, a wrong number of arguments, floor/ceil
// (jumps have no derivative), implicit products (`2t`, `2(t)`), unbalanced
// parentheses, nesting deeper than kMaxNesting, texts longer than kMaxLength
// characters, and a part that does not depend on t but is not finite for the
// identifiers' values (`ln(alpha-30)` with alpha = 30).
//
// Compilation: parse to a tree; fold every part that does not depend on t into
// one constant, and a product with a constant zero into that zero (its other
// factor is never evaluated: `0*ln(t-1)` is 0 at t = 0.5); emit a flat
// postfix program, with constant operands stored in the instruction
// (`omega*t + phase` is: push t, multiply by omega, add phase).
//
// Evaluation runs the program on triples (s, ds/dt, d2s/dt2) held on a
// fixed-size stack of kMaxStackDepth slots on the C++ stack: no allocation,
// nothing mutable in the object (one function may be evaluated from several
// threads). Each instruction combines its operands exactly:
//   a*b  -> (ab, a'b + ab', a''b + 2a'b' + ab'')
//   a/b  -> q = a/b, q' = (a' - q b')/b, q'' = (a'' - 2q'b' - q b'')/b
//   f(u) -> (f(u), f'(u) u', f''(u) u'^2 + f'(u) u'')    (chain rule)
//   u^n, n constant: the power rule (n = 0, 1, 2 without 0*inf terms)
//   a^b, b depending on t: through exp(b ln a), so a must be > 0
//   atan(y, x) -> angle' = (x y' - y x')/(x^2 + y^2), and its derivative
//   abs, min, max: the derivatives of the active branch; at a tie (abs at 0,
//     min(a, b) with a = b) the branch that is active just after t, found by
//     comparing rates, then accelerations (abs(t) at t = 0 has rate 1).
//   sign: 0 rate and acceleration.
// A result (value or either derivative) that is not finite throws
// SimulationError naming the expression, t and the first part of it that
// went non-finite: "m.xml:3: time function '2 + 3*ln(t-1)' is not finite at
// t = 0.5: its part 'ln(t-1)' is not (value nan, rate -2, acceleration -4)".

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "mech/time_function.h"

namespace mechflow::scripting {

class IdentifierTable;

class JetExpression final : public mech::TimeFunction {
 public:
  // Slots of the evaluation stack; deeper expressions are refused at
  // compilation. Constant operands take no slot, so `a*t + b*t^2` needs 2;
  // each level of parentheses on the right of an operator whose left side
  // depends on t needs one more.
  static constexpr int kMaxStackDepth = 32;
  // Parentheses, unary signs and function calls nested deeper than this are
  // refused (the parser is recursive).
  static constexpr int kMaxNesting = 100;
  // Longer texts are refused: compilation recurses along chains like
  // t+t+..., one level per operator; at 10000 characters that overflowed
  // the stack of a sanitizer build (found by its test run).
  static constexpr int kMaxLength = 2000;

  // Compiles `text` (grammar above) with the identifiers' current values.
  // `what` starts every message ("model.xml:12: joint 'j1' transformation 2").
  // Throws InputError.
  JetExpression(const std::string& text, const IdentifierTable& identifiers, const std::string& what);

  // s(t) and its first two derivatives. Allocates nothing; throws
  // SimulationError when any of the three is not finite.
  mech::Jet Evaluate(double t) const override;

  // False when the expression does not contain t: then Evaluate returns the
  // same value for every t with zero derivatives.
  bool depends_on_time() const { return depends_on_time_; }
  const std::string& text() const { return text_; }
  const std::string& what() const { return what_; }
  // Lower-case names of the identifiers read at compilation, in order of first use.
  const std::vector<std::string>& identifiers_used() const { return identifiers_used_; }
  // Length of the compiled program (1 for a constant); for tests and tuning.
  int num_instructions() const { return static_cast<int>(program_.size()); }
  // Stack slots the program needs (<= kMaxStackDepth).
  int stack_depth() const { return stack_depth_; }

 private:
  friend class JetExpressionCompiler;  // in jet_expression_compiler.cc: builds program_

  enum class Op : std::uint8_t {
    kConst,  // push c
    kTime,   // push (t, 1, 0)
    kNeg,    // x -> -x
    kAdd,    // a b -> a+b
    kSub,    // a b -> a-b
    kMul,    // a b -> a*b
    kDiv,    // a b -> a/b
    kPow,    // a b -> a^b
    kAddC,   // x -> x+c
    kSubC,   // x -> x-c
    kRSubC,  // x -> c-x
    kMulC,   // x -> x*c
    kDivC,   // x -> x/c
    kRDivC,  // x -> c/x
    kPowC,   // x -> x^c
    kRPowC,  // x -> c^x
    kMin,    // a b -> min(a, b)
    kMax,    // a b -> max(a, b)
    kAtan2,  // y x -> atan(y, x)
    kSin,
    kCos,
    kTan,
    kAsin,
    kAcos,
    kAtan,
    kSinh,
    kCosh,
    kTanh,
    kExp,
    kLn,
    kSqrt,
    kSqr,
    kAbs,
    kSign,
  };
  struct Instruction {
    Op op;
    double c = 0.0;  // the constant of kConst and the *C forms
  };

  // Runs `size` instructions at time t. With kFindFailure it stops at the
  // first instruction whose result is not finite and stores its index in
  // *failed (else -1). Also folds constants during compilation.
  template <bool kFindFailure>
  static mech::Jet RunProgram(const Instruction* code, int size, double t, int* failed);
  [[noreturn]] void ThrowNotFinite(double t, const mech::Jet& result) const;

  std::string text_, what_;
  std::vector<Instruction> program_;
  std::vector<std::pair<int, int>> spans_;  // [begin, end) in text_ of each instruction, for messages
  std::vector<std::string> identifiers_used_;
  int stack_depth_ = 0;
  bool depends_on_time_ = false;
};

// The value of an expression of the same grammar that must not contain t
// (e.g. "alpha*pi/180"), for callers that need a number. Throws InputError
// starting with `what` when it does not compile, contains t or is not finite.
double EvaluateConstantExpression(const std::string& text, const IdentifierTable& identifiers, const std::string& what);

}  // namespace mechflow::scripting
