#pragma once
// The exact derivative rules of a JetExpression (scripting/jet_expression.h):
// each operation on (value, d/dt, d2/dt2) triples, as the evaluator and the
// compiler's constant folding apply them. Internal to the expression's two
// source files.

#include <charconv>
#include <cmath>
#include <limits>
#include <string>

namespace mechflow::scripting::jet {

// (value, d/dt, d2/dt2); no default member initialisers, so that the
// evaluation stack costs nothing to set up
struct Triple {
  double v, d, dd;
};

inline bool IsFinite(const Triple& x) { return std::isfinite(x.v) && std::isfinite(x.d) && std::isfinite(x.dd); }

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// f(u), given f, f' and f'' at u.v: the chain rule to second order
inline Triple Chain(const Triple& u, double f, double f1, double f2) { return {f, f1 * u.d, f2 * u.d * u.d + f1 * u.dd}; }

inline Triple Multiply(const Triple& a, const Triple& b) {
  return {a.v * b.v, a.d * b.v + a.v * b.d, a.dd * b.v + 2 * a.d * b.d + a.v * b.dd};
}

// q = a/b: q' = (a' - q b')/b, q'' = (a'' - 2 q' b' - q b'')/b
inline Triple Divide(const Triple& a, const Triple& b) {
  const double q = a.v / b.v;
  const double q1 = (a.d - q * b.d) / b.v;
  return {q, q1, (a.dd - 2 * q1 * b.d - q * b.dd) / b.v};
}

// c/x for a constant c: Divide with a' = a'' = 0
inline Triple DivideInto(double c, const Triple& x) {
  const double q = c / x.v;
  const double q1 = -q * x.d / x.v;
  return {q, q1, (-2 * q1 * x.d - q * x.dd) / x.v};
}

// x^n for a constant n; n = 0, 1, 2 avoid the 0*inf of the general rule at x = 0
inline Triple PowerOfConstant(const Triple& x, double n) {
  if (n == 0) return {std::pow(x.v, n), 0, 0};
  if (n == 1) return {std::pow(x.v, n), x.d, x.dd};
  if (n == 2) return Chain(x, std::pow(x.v, n), 2 * x.v, 2);
  return Chain(x, std::pow(x.v, n), n * std::pow(x.v, n - 1), n * (n - 1) * std::pow(x.v, n - 2));
}

// c^x for a constant c > 0: (c^x)' = c^x ln(c) x', (c^x)'' = c^x (ln(c) x'' + (ln(c) x')^2)
inline Triple ConstantToPower(double c, const Triple& x) {
  const double p = std::pow(c, x.v), l = std::log(c);
  const double g = l * x.d;
  return {p, p * g, p * (l * x.dd + g * g)};
}

// a^b; when b does not move at this instant the power rule, else through
// exp(b ln a) (a > 0): with g = (ln p)' = b' ln a + b a'/a,
// p' = p g, p'' = p (g' + g^2), g' = b'' ln a + 2 b' a'/a + b (a''/a - (a'/a)^2)
inline Triple Power(const Triple& a, const Triple& b) {
  if (b.d == 0 && b.dd == 0) return PowerOfConstant(a, b.v);
  const double p = std::pow(a.v, b.v), l = std::log(a.v), r = a.d / a.v;
  const double g = b.d * l + b.v * r;
  const double g1 = b.dd * l + 2 * b.d * r + b.v * (a.dd / a.v - r * r);
  return {p, p * g, p * (g1 + g * g)};
}

// angle of (x, y): with N = x y' - y x' and D = x^2 + y^2, angle' = N/D and
// angle'' = (N' - angle' D')/D, N' = x y'' - y x'', D' = 2 (x x' + y y')
inline Triple Atan2(const Triple& y, const Triple& x) {
  const double den = x.v * x.v + y.v * y.v;
  const double w = (x.v * y.d - y.v * x.d) / den;
  const double num1 = x.v * y.dd - y.v * x.dd;
  const double den1 = 2 * (x.v * x.d + y.v * y.d);
  return {std::atan2(y.v, x.v), w, (num1 - w * den1) / den};
}

// true when a <= b just after this instant: compare values, then rates, then accelerations
inline bool NotAboveJustAfter(const Triple& a, const Triple& b) {
  if (a.v != b.v) return a.v < b.v;
  if (a.d != b.d) return a.d < b.d;
  return a.dd <= b.dd;
}

// the derivatives of the branch that is active (just after the instant, at a tie);
// NaN is passed on rather than lost in a comparison
inline Triple Min(const Triple& a, const Triple& b) {
  if (std::isnan(a.v) || std::isnan(b.v)) return {kNaN, kNaN, kNaN};
  return NotAboveJustAfter(a, b) ? a : b;
}
inline Triple Max(const Triple& a, const Triple& b) {
  if (std::isnan(a.v) || std::isnan(b.v)) return {kNaN, kNaN, kNaN};
  return NotAboveJustAfter(b, a) ? a : b;
}

// |x| with the slope of the side x is on (or moves to, at x = 0)
inline Triple Abs(const Triple& x) {
  const double s = x.v > 0    ? 1.0
                   : x.v < 0  ? -1.0
                   : x.d > 0  ? 1.0
                   : x.d < 0  ? -1.0
                   : x.dd > 0 ? 1.0
                   : x.dd < 0 ? -1.0
                              : 0.0;
  return {std::abs(x.v), s * x.d, s * x.dd};
}

inline Triple Sign(const Triple& x) { return {x.v > 0 ? 1.0 : x.v < 0 ? -1.0 : x.v == 0 ? 0.0 : x.v, 0, 0}; }

// shortest text that reads back as the same double ("0.1", "-inf"); "nan"
// whatever the sign bit (which depends on the CPU)
inline std::string Number(double x) {
  if (std::isnan(x)) return "nan";
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, x);
  return std::string(buffer, result.ptr);
}

}  // namespace mechflow::scripting::jet
