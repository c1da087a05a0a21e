// The compiler of a JetExpression: text -> tokens -> tree (constants folded)
// -> postfix program (the grammar and the folding rules are in
// scripting/jet_expression.h).
#include "scripting/jet_expression.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <numbers>
#include <string_view>

#include "blocks/support/suggest.h"
#include "mech/errors.h"
#include "scripting/identifiers.h"
#include "scripting/jet_rules.h"

namespace mechflow::scripting {
namespace {

using mech::Jet;
using namespace jet;

// ---------------------------------------------------------------------------
// names

struct FunctionInfo {
  const char* name;
  int min_arguments, max_arguments;
};
constexpr int kAny = 1 << 20;
constexpr FunctionInfo kFunctions[] = {
    {"sin", 1, 1},    {"cos", 1, 1},    {"tan", 1, 1},    {"asin", 1, 1}, {"acos", 1, 1}, {"atan", 1, 2},
    {"arcsin", 1, 1}, {"arccos", 1, 1}, {"arctan", 1, 2}, {"sinh", 1, 1}, {"cosh", 1, 1}, {"tanh", 1, 1},
    {"exp", 1, 1},    {"ln", 1, 1},     {"log", 1, 1},    {"sqrt", 1, 1}, {"sqr", 1, 1},  {"abs", 1, 1},
    {"sign", 1, 1},   {"min", 2, kAny}, {"max", 2, kAny},
};

const FunctionInfo* FindFunction(const std::string& lower) {
  for (const FunctionInfo& f : kFunctions)
    if (lower == f.name) return &f;
  return nullptr;
}

std::vector<std::string> FunctionNames() {
  std::vector<std::string> names;
  for (const FunctionInfo& f : kFunctions) names.push_back(f.name);
  return names;
}

constexpr const char* kLuaKeywords[] = {"and",      "break",  "do",   "else", "elseif", "end",  "false", "for",
                                        "function", "goto",   "if",   "in",   "local",  "nil",  "not",   "or",
                                        "repeat",   "return", "then", "true", "until",  "while"};

bool IsLuaKeyword(const std::string& lower) {
  return std::find_if(std::begin(kLuaKeywords), std::end(kLuaKeywords), [&](const char* k) { return lower == k; }) !=
         std::end(kLuaKeywords);
}

// the Lua tokens that are not part of a time function, longest first
constexpr const char* kLuaSymbols[] = {"...", "--", "..", "==", "~=", "<=", ">=", "<<", ">>", "//",
                                       "::",  "<",  ">",  "=",  "~",  "%",  "#",  "&",  "|",  "[",
                                       "]",   "{",  "}",  ";",  ":",  ".",  "\"", "'"};

bool IsNameStart(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool IsNameChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

}  // namespace

// ---------------------------------------------------------------------------
// compiler: text -> tokens -> tree (constants folded) -> postfix program

class JetExpressionCompiler {
 public:
  using Op = JetExpression::Op;
  using Instruction = JetExpression::Instruction;

  JetExpressionCompiler(const IdentifierTable& identifiers, JetExpression* out)
      : s_(out->text_), ids_(identifiers), out_(out) {}

  void Compile() {
    if (s_.size() > static_cast<std::size_t>(JetExpression::kMaxLength))
      throw InputError(out_->what_ + ": time function of " + std::to_string(s_.size()) + " characters: longer than " +
                       std::to_string(JetExpression::kMaxLength) + "; simplify it or use identifiers");
    Next();
    const int root = Expression();
    if (token_.kind != Token::kEnd) FailAfterOperand("an operator (+ - * / ^) or the end of the expression");
    Emit(root);
    if (max_depth_ > JetExpression::kMaxStackDepth)
      Fail("needs " + std::to_string(max_depth_) + " evaluation stack slots, more than the " +
           std::to_string(JetExpression::kMaxStackDepth) +
           " available; write deeply nested parts first in sums and products, or simplify");
    out_->stack_depth_ = max_depth_;
  }

 private:
  struct Token {
    enum Kind { kNumber, kName, kSymbol, kEnd } kind = kEnd;
    int begin = 0, end = 0;  // [begin, end) in the text
    double number = 0.0;
    std::string text;  // lower-case for names
  };
  struct Node {
    Op op;
    double value = 0.0;  // kConst
    int a = -1, b = -1;  // operands
    int begin = 0, end = 0;
    bool constant = false;
  };

  // --- messages

  [[noreturn]] void Fail(const std::string& message) const {
    throw InputError(out_->what_ + ": time function '" + s_ + "': " + message);
  }

  std::string Column(int at) const { return " at column " + std::to_string(at + 1); }

  // a token and where it is, for "found ..."
  std::string Found(const Token& token) const {
    if (token.kind == Token::kEnd) return "the end of the expression";
    if (token.kind == Token::kSymbol && (s_[token.begin] == '"' || s_[token.begin] == '\''))
      return "a string" + Column(token.begin);
    return "'" + s_.substr(token.begin, token.end - token.begin) + "'" + Column(token.begin);
  }

  // why a token that looks like Lua is not accepted ("" for others)
  std::string WhyNot(const Token& token) const {
    const std::string text = s_.substr(token.begin, token.end - token.begin);
    if (token.kind == Token::kName && IsLuaKeyword(token.text))
      return "Lua keywords (and, or, not, nil, ...) are not part of a time function";
    if (token.kind != Token::kSymbol) return "";
    if (text == "--") return "in Lua '--' starts a comment; write '- -' or '+' to negate twice";
    if (text == "..") return "'..' joins strings in Lua; time functions have only + - * / ^";
    if (text == "//" || text == "%" || text == "&" || text == "|" || text == "~" || text == "<<" || text == ">>")
      return "time functions have only the operators + - * / ^";
    if (text == "==" || text == "~=" || text == "<" || text == "<=" || text == ">" || text == ">=")
      return "time functions have no comparisons";
    if (text == "\"" || text == "'") return "time functions have no strings";
    if (text == "=") return "a time function is an expression, not an assignment";
    return "";
  }

  // a token that cannot come where an operand (number, name, '(') must
  [[noreturn]] void FailExpectedOperand() const {
    const std::string why = WhyNot(token_);
    Fail("expected a number, a name, '(' or a sign, found " + Found(token_) + (why.empty() ? "" : "; " + why));
  }

  // after a complete operand, a token that cannot follow it
  [[noreturn]] void FailAfterOperand(const std::string& expected) const {
    std::string why = WhyNot(token_);
    if (token_.kind == Token::kNumber || (token_.kind == Token::kName && why.empty()) || IsSymbol('('))
      why = "write '*' for a product";
    Fail("expected " + expected + ", found " + Found(token_) + (why.empty() ? "" : "; " + why));
  }

  // --- tokens

  void Next() {
    int i = token_.end;  // 0 before the first token
    const int n = static_cast<int>(s_.size());
    while (i < n && std::isspace(static_cast<unsigned char>(s_[i]))) ++i;
    token_ = Token();
    token_.begin = i;
    if (i >= n) {
      token_.kind = Token::kEnd;
      token_.end = n;
      return;
    }
    const char c = s_[i];
    if (std::isdigit(static_cast<unsigned char>(c)) ||
        (c == '.' && i + 1 < n && std::isdigit(static_cast<unsigned char>(s_[i + 1]))))
      return ReadNumber(i);
    if (IsNameStart(c)) {
      int j = i;
      while (j < n && IsNameChar(s_[j])) ++j;
      token_.kind = Token::kName;
      token_.end = j;
      token_.text = ToLower(s_.substr(i, j - i));
      return;
    }
    token_.kind = Token::kSymbol;
    token_.end = i + 1;
    for (const char* symbol : kLuaSymbols) {
      const std::string_view sv(symbol);
      if (std::string_view(s_).substr(i, sv.size()) == sv) {
        token_.end = i + static_cast<int>(sv.size());
        break;
      }
    }
  }

  // a numeral as Lua reads it: digits, '.', exponent with sign; then letters
  // glued to it make it malformed ("2t", "1.2.3"), as in Lua
  void ReadNumber(int i) {
    const int n = static_cast<int>(s_.size());
    const bool hex = s_[i] == '0' && i + 1 < n && (s_[i + 1] == 'x' || s_[i + 1] == 'X');
    const char* exponent = hex ? "Pp" : "Ee";
    int j = hex ? i + 2 : i;
    while (j < n) {
      if (s_[j] == exponent[0] || s_[j] == exponent[1]) {
        ++j;
        if (j < n && (s_[j] == '+' || s_[j] == '-')) ++j;
      } else if (std::isxdigit(static_cast<unsigned char>(s_[j])) || s_[j] == '.') {
        ++j;
      } else {
        break;
      }
    }
    while (j < n && (IsNameChar(s_[j]) || s_[j] == '.')) ++j;
    token_.kind = Token::kNumber;
    token_.end = j;
    const char* first = s_.data() + (hex ? i + 2 : i);
    const char* last = s_.data() + j;
    const auto [ptr, ec] =
        std::from_chars(first, last, token_.number, hex ? std::chars_format::hex : std::chars_format::general);
    const std::string text = s_.substr(i, j - i);
    if (ec == std::errc::result_out_of_range) Fail("the number '" + text + "'" + Column(i) + " is out of range");
    if (ec != std::errc() || ptr != last || first == last)
      Fail("malformed number '" + text + "'" + Column(i) + " (write '*' for a product, as in '2*t')");
  }

  bool IsSymbol(char c) const {
    return token_.kind == Token::kSymbol && token_.end - token_.begin == 1 && s_[token_.begin] == c;
  }

  // --- tree

  int Add(Node node) {
    nodes_.push_back(node);
    return static_cast<int>(nodes_.size()) - 1;
  }

  int Leaf(Op op, double value, int begin, int end) {
    Node node{op, value};
    node.begin = begin;
    node.end = end;
    node.constant = op == Op::kConst;
    return Add(node);
  }

  // an operation on one or two operands; folded into a constant when they are
  int Operation(Op op, int a, int b, int begin, int end) {
    Node node{op};
    node.a = a;
    node.b = b;
    node.begin = begin;
    node.end = end;
    node.constant = nodes_[a].constant && (b < 0 || nodes_[b].constant);
    // A product with a constant zero is that zero: a part an identifier
    // switches off (ampl*sin(2*pi*om*t) with ampl = 0) costs nothing at run
    // time, and its other factor is not evaluated at all.
    const auto zero = [&](int n) { return n >= 0 && nodes_[n].constant && nodes_[n].value == 0.0; };
    if (op == Op::kMul && !node.constant && (zero(a) || zero(b))) {
      node.op = Op::kConst;
      node.value = zero(a) ? nodes_[a].value : nodes_[b].value;
      node.a = node.b = -1;
      node.constant = true;
      return Add(node);
    }
    if (node.constant) {
      // the same code as at run time, on operands without derivatives
      Instruction program[3] = {{Op::kConst, nodes_[a].value}, {Op::kConst, b < 0 ? 0.0 : nodes_[b].value}, {op}};
      if (b < 0) program[1] = program[2];
      const double value = JetExpression::RunProgram<false>(program, b < 0 ? 2 : 3, 0.0, nullptr).value;
      if (!std::isfinite(value))
        Fail("'" + s_.substr(begin, end - begin) + "' is " + Number(value) +
             " for the identifiers' values (it does not depend on t)");
      node.op = Op::kConst;
      node.value = value;
      node.a = node.b = -1;
    }
    return Add(node);
  }

  // --- grammar (see the header)

  int Expression() {
    int a = Term();
    for (;;) {
      const Op op = IsSymbol('+') ? Op::kAdd : IsSymbol('-') ? Op::kSub : Op::kConst;
      if (op == Op::kConst) return a;
      Next();
      const int b = Term();
      a = Operation(op, a, b, nodes_[a].begin, nodes_[b].end);
    }
  }

  int Term() {
    int a = Unary();
    for (;;) {
      const Op op = IsSymbol('*') ? Op::kMul : IsSymbol('/') ? Op::kDiv : Op::kConst;
      if (op == Op::kConst) return a;
      Next();
      const int b = Unary();
      a = Operation(op, a, b, nodes_[a].begin, nodes_[b].end);
    }
  }

  int Unary() {
    if (++nesting_ > JetExpression::kMaxNesting)
      Fail("nested more than " + std::to_string(JetExpression::kMaxNesting) + " deep" + Column(token_.begin));
    int result;
    if (IsSymbol('-')) {
      const int begin = token_.begin;
      Next();
      const int a = Unary();
      result = Operation(Op::kNeg, a, -1, begin, nodes_[a].end);
    } else if (IsSymbol('+')) {
      Next();
      result = Unary();
    } else {
      result = Power();
    }
    --nesting_;
    return result;
  }

  int Power() {
    const int a = Primary();
    if (!IsSymbol('^')) return a;
    Next();
    const int b = Unary();  // right-associative, and 2^-1 is allowed
    return Operation(Op::kPow, a, b, nodes_[a].begin, nodes_[b].end);
  }

  int Primary() {
    const Token token = token_;
    if (token.kind == Token::kNumber) {
      Next();
      return Leaf(Op::kConst, token.number, token.begin, token.end);
    }
    if (token.kind == Token::kName && !IsLuaKeyword(token.text)) {
      Next();
      return Name(token);
    }
    if (IsSymbol('(')) {
      Next();
      const int inner = Expression();
      if (!IsSymbol(')')) FailAfterOperand("an operator (+ - * / ^) or ')' closing the '('" + Column(token.begin));
      nodes_[inner].begin = token.begin;  // messages quote the parentheses too
      nodes_[inner].end = token_.end;
      Next();
      return inner;
    }
    FailExpectedOperand();
  }

  // a name; token_ is the token after it
  int Name(const Token& name) {
    const std::string& lower = name.text;
    const std::string original = s_.substr(name.begin, name.end - name.begin);
    if (IsSymbol('.') || IsSymbol(':')) {
      std::string message = "'" + original + s_[token_.begin] + "'" + Column(name.begin) +
                            " is Lua field access, which time functions do not have";
      Next();
      if (lower == "math" && token_.kind == Token::kName && (FindFunction(token_.text) || token_.text == "pi"))
        message += "; write '" + token_.text + "' alone";
      Fail(message);
    }
    const bool called = IsSymbol('(');
    const FunctionInfo* function = FindFunction(lower);
    if (lower == "floor" || lower == "ceil")
      Fail("'" + original + "'" + Column(name.begin) +
           " is not allowed in a time function: its jumps have no derivative");
    if (called) {
      if (function) return Call(*function, name);
      if (lower == "t" || lower == "pi" || ids_.Find(lower) >= 0)
        Fail("'" + original + "'" + Column(name.begin) + " is not a function; write '*' for a product");
      Fail("unknown function '" + original + "'" + Column(name.begin) + blocks::DidYouMean(lower, FunctionNames()) +
           "; expected one of " + blocks::JoinNames(FunctionNames()));
    }
    if (function) Fail("the function '" + original + "'" + Column(name.begin) + " needs its arguments in parentheses");
    if (lower == "t") {
      out_->depends_on_time_ = true;
      return Leaf(Op::kTime, 0.0, name.begin, name.end);
    }
    if (lower == "pi") return Leaf(Op::kConst, std::numbers::pi, name.begin, name.end);
    const int index = ids_.Find(lower);
    if (index >= 0) {
      auto& used = out_->identifiers_used_;
      if (std::find(used.begin(), used.end(), lower) == used.end()) used.push_back(lower);
      return Leaf(Op::kConst, ids_.value(index), name.begin, name.end);
    }
    if (lower == "x" || lower == "v")
      Fail("'" + original + "'" + Column(name.begin) +
           ": x and v are arguments of force laws; a time function depends on t alone");
    std::vector<std::string> candidates = ids_.Names();
    candidates.push_back("t");
    candidates.push_back("pi");
    // a one-letter name is close to too many others for a suggestion to help
    const std::string hint = lower.size() > 1 ? blocks::DidYouMean(lower, candidates) : "";
    Fail("unknown name '" + original + "'" + Column(name.begin) + hint + "; expected t, pi or an identifier");
  }

  // f(arguments); token_ is the '('
  int Call(const FunctionInfo& f, const Token& name) {
    const int open = token_.begin;
    Next();
    std::vector<int> arguments;
    if (!IsSymbol(')')) {
      for (;;) {
        arguments.push_back(Expression());
        if (IsSymbol(')')) break;
        if (!IsSymbol(','))
          FailAfterOperand("an operator (+ - * / ^), ',' or ')' closing the arguments of '" + name.text + "'" +
                           Column(open));
        Next();
      }
    }
    const int end = token_.end;
    Next();
    const int count = static_cast<int>(arguments.size());
    if (count < f.min_arguments || count > f.max_arguments) {
      const std::string expected =
          f.max_arguments == kAny ? std::to_string(f.min_arguments) + " or more arguments"
          : f.min_arguments == f.max_arguments
              ? std::to_string(f.min_arguments) + (f.min_arguments == 1 ? " argument" : " arguments")
              : std::to_string(f.min_arguments) + " or " + std::to_string(f.max_arguments) + " arguments";
      std::string hint;
      if ((name.text == "ln" || name.text == "log") && count == 2) hint = " (for another base write ln(x)/ln(b))";
      Fail("'" + s_.substr(name.begin, name.end - name.begin) + "'" + Column(name.begin) + " takes " + expected +
           ", found " + std::to_string(count) + hint);
    }
    const std::string& n = name.text;
    if (n == "min" || n == "max") {
      int a = arguments[0];
      for (int k = 1; k < count; ++k) a = Operation(n == "min" ? Op::kMin : Op::kMax, a, arguments[k], name.begin, end);
      return a;
    }
    if (count == 2) return Operation(Op::kAtan2, arguments[0], arguments[1], name.begin, end);  // atan(y, x)
    const Op op = n == "sin"                     ? Op::kSin
                  : n == "cos"                   ? Op::kCos
                  : n == "tan"                   ? Op::kTan
                  : n == "asin" || n == "arcsin" ? Op::kAsin
                  : n == "acos" || n == "arccos" ? Op::kAcos
                  : n == "atan" || n == "arctan" ? Op::kAtan
                  : n == "sinh"                  ? Op::kSinh
                  : n == "cosh"                  ? Op::kCosh
                  : n == "tanh"                  ? Op::kTanh
                  : n == "exp"                   ? Op::kExp
                  : n == "ln" || n == "log"      ? Op::kLn
                  : n == "sqrt"                  ? Op::kSqrt
                  : n == "sqr"                   ? Op::kSqr
                  : n == "abs"                   ? Op::kAbs
                                                 : Op::kSign;
    return Operation(op, arguments[0], -1, name.begin, end);
  }

  // --- postfix program

  void Push(Op op, double c, const Node& node, int depth_change) {
    out_->program_.push_back({op, c});
    out_->spans_.emplace_back(node.begin, node.end);
    depth_ += depth_change;
    max_depth_ = std::max(max_depth_, depth_);
  }

  // emits node n; a constant operand goes into the instruction
  void Emit(int n) {
    const Node node = nodes_[n];
    if (node.op == Op::kConst || node.op == Op::kTime) return Push(node.op, node.value, node, +1);
    if (node.b < 0) {
      Emit(node.a);
      return Push(node.op, 0.0, node, 0);
    }
    const Node& a = nodes_[node.a];
    const Node& b = nodes_[node.b];
    Op with_constant = Op::kConst;  // none
    if (b.constant) {
      with_constant = node.op == Op::kAdd   ? Op::kAddC
                      : node.op == Op::kSub ? Op::kSubC
                      : node.op == Op::kMul ? Op::kMulC
                      : node.op == Op::kDiv ? Op::kDivC
                      : node.op == Op::kPow ? Op::kPowC
                                            : Op::kConst;
      if (with_constant != Op::kConst) {
        Emit(node.a);
        return Push(with_constant, b.value, node, 0);
      }
    } else if (a.constant) {
      // c + x and c * x as x + c and x * c: exactly the same numbers
      with_constant = node.op == Op::kAdd   ? Op::kAddC
                      : node.op == Op::kSub ? Op::kRSubC
                      : node.op == Op::kMul ? Op::kMulC
                      : node.op == Op::kDiv ? Op::kRDivC
                      : node.op == Op::kPow ? Op::kRPowC
                                            : Op::kConst;
      if (with_constant != Op::kConst) {
        Emit(node.b);
        return Push(with_constant, a.value, node, 0);
      }
    }
    Emit(node.a);
    Emit(node.b);
    Push(node.op, 0.0, node, -1);
  }

  const std::string& s_;
  const IdentifierTable& ids_;
  JetExpression* out_;
  Token token_;
  std::vector<Node> nodes_;
  int nesting_ = 0;
  int depth_ = 0, max_depth_ = 0;
};

// ---------------------------------------------------------------------------
// JetExpression

JetExpression::JetExpression(const std::string& text, const IdentifierTable& identifiers,
                                           const std::string& what)
    : text_(text), what_(what) {
  JetExpressionCompiler(identifiers, this).Compile();
}

double EvaluateConstantExpression(const std::string& text, const IdentifierTable& identifiers,
                                  const std::string& what) {
  const JetExpression f(text, identifiers, what);
  if (f.depends_on_time())
    throw InputError(what + ": '" + text + "' depends on t; expected an expression of numbers and identifiers");
  return f.Evaluate(0.0).value;  // finite: a non-finite constant does not compile
}

}  // namespace mechflow::scripting
