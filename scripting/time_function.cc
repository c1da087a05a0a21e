#include "scripting/time_function.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>

#include "blocks/suggest.h"
#include "mech/errors.h"
#include "scripting/identifiers.h"

namespace mechflow::scripting {
namespace {

using mech::Jet;
using Op = CompiledTimeFunction::Op;
using Instruction = CompiledTimeFunction::Instruction;

enum Function1 { kSin, kCos, kTan, kAsin, kAcos, kAtan, kExp, kLn, kSqrt, kSqr, kAbs, kSign, kSinh, kCosh, kTanh };
enum Function2 { kMin, kMax };

struct Named {
  const char* name;
  int arity;
  int id;
};
constexpr Named kFunctions[] = {
    {"sin", 1, kSin},     {"cos", 1, kCos},       {"tan", 1, kTan},       {"asin", 1, kAsin},
    {"arcsin", 1, kAsin}, {"acos", 1, kAcos},     {"arccos", 1, kAcos},   {"atan", 1, kAtan},
    {"arctan", 1, kAtan}, {"exp", 1, kExp},       {"ln", 1, kLn},         {"log", 1, kLn},
    {"sqrt", 1, kSqrt},   {"sqr", 1, kSqr},       {"abs", 1, kAbs},       {"sign", 1, kSign},
    {"sinh", 1, kSinh},   {"cosh", 1, kCosh},     {"tanh", 1, kTanh},     {"min", 2, kMin},
    {"max", 2, kMax}};

// f(u) with f, f', f'' at u.value: the chain rule for a triple.
Jet Chain(const Jet& u, double f, double f1, double f2) {
  return {f, f1 * u.rate, f2 * u.rate * u.rate + f1 * u.acceleration};
}

Jet Apply1(int fn, const Jet& u) {
  const double x = u.value;
  switch (fn) {
    case kSin: return Chain(u, std::sin(x), std::cos(x), -std::sin(x));
    case kCos: return Chain(u, std::cos(x), -std::sin(x), -std::cos(x));
    case kTan: {
      const double tn = std::tan(x), s2 = 1 + tn * tn;
      return Chain(u, tn, s2, 2 * tn * s2);
    }
    case kAsin: {
      const double r = 1 / std::sqrt(1 - x * x);
      return Chain(u, std::asin(x), r, x * r * r * r);
    }
    case kAcos: {
      const double r = 1 / std::sqrt(1 - x * x);
      return Chain(u, std::acos(x), -r, -x * r * r * r);
    }
    case kAtan: {
      const double r = 1 / (1 + x * x);
      return Chain(u, std::atan(x), r, -2 * x * r * r);
    }
    case kExp: {
      const double e = std::exp(x);
      return Chain(u, e, e, e);
    }
    case kLn: return Chain(u, std::log(x), 1 / x, -1 / (x * x));
    case kSqrt: {
      const double s = std::sqrt(x);
      return Chain(u, s, 0.5 / s, -0.25 / (s * x));
    }
    case kSqr: return Chain(u, x * x, 2 * x, 2);
    case kAbs: {
      const double sg = x > 0 ? 1.0 : x < 0 ? -1.0 : 0.0;
      return Chain(u, std::abs(x), sg, 0);
    }
    case kSign: return {x > 0 ? 1.0 : x < 0 ? -1.0 : 0.0, 0, 0};
    case kSinh: return Chain(u, std::sinh(x), std::cosh(x), std::sinh(x));
    case kCosh: return Chain(u, std::cosh(x), std::sinh(x), std::cosh(x));
    case kTanh: {
      const double th = std::tanh(x), s2 = 1 - th * th;
      return Chain(u, th, s2, -2 * th * s2);
    }
  }
  return u;
}

Jet Multiply(const Jet& a, const Jet& b) {
  return {a.value * b.value, a.rate * b.value + a.value * b.rate,
          a.acceleration * b.value + 2 * a.rate * b.rate + a.value * b.acceleration};
}

Jet Divide(const Jet& a, const Jet& b) {
  // q = a/b: q' = (a' - q b')/b, q'' = (a'' - 2 q' b' - q b'')/b
  const double q = a.value / b.value;
  const double q1 = (a.rate - q * b.rate) / b.value;
  const double q2 = (a.acceleration - 2 * q1 * b.rate - q * b.acceleration) / b.value;
  return {q, q1, q2};
}

Jet Power(const Jet& a, const Jet& b) {
  if (b.rate == 0.0 && b.acceleration == 0.0) {  // constant exponent: power rule
    const double n = b.value, x = a.value;
    return Chain(a, std::pow(x, n), n * std::pow(x, n - 1), n * (n - 1) * std::pow(x, n - 2));
  }
  // a^b = exp(b ln a), a > 0
  const Jet ln_a = Apply1(kLn, a);
  return Apply1(kExp, Multiply(b, ln_a));
}

class Parser {
 public:
  Parser(const std::string& text, const IdentifierTable& ids, const std::string& what)
      : s_(text), ids_(ids), what_(what) {}

  std::vector<Instruction> Parse(bool* uses_time) {
    Expression();
    Skip();
    if (pos_ < s_.size()) Fail("unexpected '" + std::string(1, s_[pos_]) + "'");
    *uses_time = uses_time_;
    return std::move(tape_);
  }

 private:
  [[noreturn]] void Fail(const std::string& message) const {
    std::ostringstream out;
    out << what_ << ": time function '" << s_ << "': " << message << " at column " << pos_ + 1
        << " (expected numbers, identifiers, t, + - * / ^, parentheses and the functions sin cos tan asin acos "
           "atan exp ln sqrt sqr abs sign min max sinh cosh tanh)";
    throw InputError(out.str());
  }
  void Skip() {
    while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
  }
  bool Accept(char c) {
    Skip();
    if (pos_ < s_.size() && s_[pos_] == c) {
      ++pos_;
      return true;
    }
    return false;
  }
  void Emit(Op op, double value = 0.0, int function = 0) { tape_.push_back({op, value, function}); }

  void Expression() {  // sum := product (('+'|'-') product)*
    Product();
    for (;;) {
      if (Accept('+')) {
        Product();
        Emit(Op::kAdd);
      } else if (Accept('-')) {
        Product();
        Emit(Op::kSub);
      } else {
        return;
      }
    }
  }
  void Product() {  // product := unary (('*'|'/') unary)*
    Unary();
    for (;;) {
      if (Accept('*')) {
        Unary();
        Emit(Op::kMul);
      } else if (Accept('/')) {
        Unary();
        Emit(Op::kDiv);
      } else {
        return;
      }
    }
  }
  void Unary() {  // unary := ('-'|'+') unary | power
    if (Accept('-')) {
      Unary();
      Emit(Op::kNeg);
    } else if (Accept('+')) {
      Unary();
    } else {
      Power();
    }
  }
  void Power() {  // power := primary ('^' unary)?   (right-associative, as in Lua)
    Primary();
    if (Accept('^')) {
      Unary();
      Emit(Op::kPow);
    }
  }
  void Primary() {
    Skip();
    if (pos_ >= s_.size()) Fail("the expression ends too early");
    const char c = s_[pos_];
    if (Accept('(')) {
      Expression();
      if (!Accept(')')) Fail("')' missing");
      return;
    }
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') return Number();
    if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') return Name();
    Fail("unexpected '" + std::string(1, c) + "'");
  }
  void Number() {
    const char* begin = s_.c_str() + pos_;
    char* end = nullptr;
    const double value = std::strtod(begin, &end);
    if (end == begin) Fail("malformed number");
    pos_ += static_cast<std::size_t>(end - begin);
    Emit(Op::kConst, value);
  }
  void Name() {
    const std::size_t start = pos_;
    while (pos_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[pos_])) || s_[pos_] == '_')) ++pos_;
    const std::string name = ToLower(s_.substr(start, pos_ - start));
    Skip();
    if (pos_ < s_.size() && s_[pos_] == '(') {
      for (const Named& f : kFunctions) {
        if (name != f.name) continue;
        Accept('(');
        Expression();
        for (int k = 1; k < f.arity; ++k) {
          if (!Accept(',')) Fail(std::string(f.name) + " takes " + std::to_string(f.arity) + " arguments");
          Expression();
        }
        if (!Accept(')')) Fail("')' missing after the arguments of " + std::string(f.name));
        Emit(f.arity == 1 ? Op::kCall1 : Op::kCall2, 0.0, f.id);
        return;
      }
      pos_ = start;
      Fail("unknown function '" + name + "'");
    }
    if (pos_ + 1 < s_.size() && (s_[pos_] == '.' || s_[pos_] == ':') &&
        std::isalpha(static_cast<unsigned char>(s_[pos_ + 1]))) {
      pos_ = start;
      Fail("field access ('" + name + ".') is not part of a time function");
    }
    if (name == "t") {
      uses_time_ = true;
      return Emit(Op::kTime);
    }
    if (name == "pi") return Emit(Op::kConst, M_PI);
    const int index = ids_.Find(name);
    if (index < 0) {
      pos_ = start;
      Fail("unknown identifier '" + name + "'" + blocks::DidYouMean(name, ids_.Names()));
    }
    Emit(Op::kConst, ids_.value(index));
  }

  const std::string& s_;
  const IdentifierTable& ids_;
  const std::string& what_;
  std::size_t pos_ = 0;
  std::vector<Instruction> tape_;
  bool uses_time_ = false;
};

}  // namespace

CompiledTimeFunction::CompiledTimeFunction(const std::string& text, const IdentifierTable& identifiers,
                                           const std::string& what)
    : text_(text), what_(what) {
  tape_ = Parser(text_, identifiers, what_).Parse(&uses_time_);
  int depth = 0, max_depth = 0;
  for (const Instruction& in : tape_) {
    depth += (in.op == Op::kConst || in.op == Op::kTime) ? 1
             : (in.op == Op::kNeg || in.op == Op::kCall1) ? 0
                                                           : -1;
    max_depth = std::max(max_depth, depth);
  }
  stack_.resize(max_depth);
}

mech::Jet CompiledTimeFunction::Evaluate(double t) const {
  int top = 0;
  Jet* s = stack_.data();
  for (const Instruction& in : tape_) {
    switch (in.op) {
      case Op::kConst: s[top++] = {in.value, 0, 0}; break;
      case Op::kTime: s[top++] = {t, 1, 0}; break;
      case Op::kNeg: s[top - 1] = {-s[top - 1].value, -s[top - 1].rate, -s[top - 1].acceleration}; break;
      case Op::kCall1: s[top - 1] = Apply1(in.function, s[top - 1]); break;
      default: {
        const Jet b = s[--top];
        Jet& a = s[top - 1];
        switch (in.op) {
          case Op::kAdd: a = {a.value + b.value, a.rate + b.rate, a.acceleration + b.acceleration}; break;
          case Op::kSub: a = {a.value - b.value, a.rate - b.rate, a.acceleration - b.acceleration}; break;
          case Op::kMul: a = Multiply(a, b); break;
          case Op::kDiv: a = Divide(a, b); break;
          case Op::kPow: a = Power(a, b); break;
          case Op::kCall2: a = (in.function == kMin) == (a.value <= b.value) ? a : b; break;
          default: break;
        }
      }
    }
  }
  const Jet r = s[0];
  if (!std::isfinite(r.value) || !std::isfinite(r.rate) || !std::isfinite(r.acceleration)) {
    std::ostringstream out;
    out << what_ << ": time function '" << text_ << "' is not finite at t = " << t;
    throw SimulationError(out.str());
  }
  return r;
}

}  // namespace mechflow::scripting
