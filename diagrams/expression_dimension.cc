#include "diagrams/expression_dimension.h"

#include <cmath>
#include <vector>

#include "scripting/lua_lexer.h"

namespace mechflow::diagrams {
namespace {

// A value of the expression: of unknown dimension, a plain number (whose
// value an exponent needs), or of a known dimension.
struct Quantity {
  enum Kind { kUnknown, kNumber, kKnown } kind = kUnknown;
  Dimension dimension;
  double value = 0.0;  // kNumber only
};

Quantity Unknown() { return {}; }
Quantity Number(double value) { return {Quantity::kNumber, {}, value}; }
Quantity Known(const Dimension& d) { return {Quantity::kKnown, d, 0.0}; }

std::string Show(const Dimension& d) { return d.Describe() + " (" + d.Text() + ")"; }

// Functions whose result has no dimension, whatever their arguments.
constexpr const char* kNumberFunctions[] = {"sin",  "cos",  "tan",  "asin", "acos", "atan",  "arcsin", "arccos",
                                            "arctan", "exp", "ln",  "log",  "sinh", "cosh",  "tanh",   "sign", "STEP"};
// Functions whose result has the dimension of their arguments (all alike).
constexpr const char* kSameFunctions[] = {"abs", "min", "max", "floor", "ceil"};

template <std::size_t N>
bool Contains(const char* const (&list)[N], const std::string& name) {
  for (const char* s : list)
    if (name == s) return true;
  return false;
}

class Reader {
 public:
  Reader(const std::string& text, const std::function<std::optional<Dimension>(const std::string&)>& dimension_of)
      : dimension_of_(dimension_of) {
    for (std::size_t i = 0, end = 0; i < text.size(); i = end) {
      const scripting::LuaToken kind = scripting::NextLuaToken(text, i, &end);
      if (kind == scripting::LuaToken::kSpace) continue;
      if (kind == scripting::LuaToken::kComment || kind == scripting::LuaToken::kString) followed_ = false;
      tokens_.push_back({kind, text.substr(i, end - i)});
    }
  }

  ExpressionDimension Read() {
    ExpressionDimension result;
    if (!followed_ || tokens_.empty()) return result;
    const Quantity q = Sum();
    result.conflict = conflict_;
    if (!followed_ || at_ != tokens_.size() || q.kind == Quantity::kUnknown) return result;
    result.known = true;
    result.plain_number = q.kind == Quantity::kNumber;
    result.dimension = q.kind == Quantity::kKnown ? q.dimension : Dimension();
    return result;
  }

 private:
  struct Token {
    scripting::LuaToken kind;
    std::string text;
  };
  bool Is(const char* text) const { return at_ < tokens_.size() && tokens_[at_].text == text; }
  bool Take(const char* text) {
    if (!Is(text)) return false;
    ++at_;
    return true;
  }

  // a + b, a - b: alike, or a number taking the other's dimension
  Quantity Add(const Quantity& a, const Quantity& b, bool minus) {
    if (a.kind == Quantity::kUnknown || b.kind == Quantity::kUnknown) return Unknown();
    if (a.kind == Quantity::kNumber && b.kind == Quantity::kNumber) return Number(minus ? a.value - b.value : a.value + b.value);
    if (a.kind == Quantity::kNumber) return b;
    if (b.kind == Quantity::kNumber) return a;
    if (a.dimension.SameAs(b.dimension)) return a;
    if (conflict_.empty())
      conflict_ = std::string(minus ? "subtracts " : "adds ") + Show(a.dimension) + " and " + Show(b.dimension);
    return Unknown();
  }
  static Quantity Multiply(const Quantity& a, const Quantity& b, double power) {
    if (a.kind == Quantity::kUnknown || b.kind == Quantity::kUnknown) return Unknown();
    if (a.kind == Quantity::kNumber && b.kind == Quantity::kNumber)
      return Number(power > 0 ? a.value * b.value : a.value / b.value);
    return Known(a.dimension.Times(b.dimension, power));
  }
  static Quantity Raise(const Quantity& base, const Quantity& exponent) {
    if (base.kind == Quantity::kUnknown || exponent.kind == Quantity::kUnknown) return Unknown();
    if (exponent.kind == Quantity::kNumber) {
      if (base.kind == Quantity::kNumber) return Number(std::pow(base.value, exponent.value));
      return Known(base.dimension.Power(exponent.value));
    }
    // an exponent of known dimension: only a dimensionless base keeps one
    return base.kind == Quantity::kNumber || base.dimension.IsNumber() ? Known(Dimension()) : Unknown();
  }

  Quantity Sum() {
    Quantity q = Product();
    while (followed_) {
      if (Take("+")) q = Add(q, Product(), false);
      else if (Take("-")) q = Add(q, Product(), true);
      else break;
    }
    return q;
  }
  Quantity Product() {
    Quantity q = Unary();
    while (followed_) {
      if (Take("*")) q = Multiply(q, Unary(), 1.0);
      else if (Take("/")) q = Multiply(q, Unary(), -1.0);
      else break;
    }
    return q;
  }
  Quantity Unary() {
    if (Take("-")) {
      Quantity q = Unary();
      if (q.kind == Quantity::kNumber) q.value = -q.value;
      return q;
    }
    return Power();
  }
  Quantity Power() {
    const Quantity base = Primary();
    if (!Take("^")) return base;
    return Raise(base, Unary());  // right-associative: 2^-x^2 is 2^(-(x^2))
  }
  Quantity Primary() {
    if (at_ >= tokens_.size()) return Fail();
    const Token token = tokens_[at_++];
    if (token.kind == scripting::LuaToken::kNumber) {
      char* end = nullptr;
      const double value = std::strtod(token.text.c_str(), &end);
      return end && *end == '\0' ? Number(value) : Unknown();
    }
    if (token.text == "(") {
      const Quantity q = Sum();
      return Take(")") ? q : Fail();
    }
    if (token.kind != scripting::LuaToken::kName) return Fail();
    if (Take("(")) return Call(token.text);
    if (Is(".") || Is(":") || Is("[")) return Fail();
    if (token.text == "pi") return Number(M_PI);
    if (token.text == "t") return Known(Dimension{{0, 0, 1}});
    const std::optional<Dimension> d = dimension_of_(token.text);
    return d ? Known(*d) : Unknown();
  }
  Quantity Call(const std::string& name) {
    std::vector<Quantity> arguments;
    if (!Take(")")) {
      do arguments.push_back(Sum());
      while (followed_ && Take(","));
      if (!Take(")")) return Fail();
    }
    if (Contains(kNumberFunctions, name)) return Known(Dimension());
    if (arguments.size() == 1 && name == "sqrt") return Raise(arguments[0], Number(0.5));
    if (arguments.size() == 1 && name == "sqr") return Raise(arguments[0], Number(2.0));
    if (!Contains(kSameFunctions, name) || arguments.empty()) return Unknown();
    Quantity q = arguments[0];
    for (std::size_t i = 1; i < arguments.size(); ++i) q = Add(q, arguments[i], false);
    return q.kind == Quantity::kNumber ? Known(Dimension()) : q;
  }
  // not followed: the expression's dimension stays unknown
  Quantity Fail() {
    followed_ = false;
    at_ = tokens_.size();
    return Unknown();
  }

  const std::function<std::optional<Dimension>(const std::string&)>& dimension_of_;
  std::vector<Token> tokens_;
  std::size_t at_ = 0;
  bool followed_ = true;
  std::string conflict_;
};

}  // namespace

ExpressionDimension InferDimension(const std::string& text,
                                   const std::function<std::optional<Dimension>(const std::string&)>& dimension_of) {
  return Reader(text, dimension_of).Read();
}

}  // namespace mechflow::diagrams
