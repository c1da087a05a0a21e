// Time functions of prescribed motions: values and exact first and second
// derivatives against closed forms, the grammar against Lua, every kind of
// error, and evaluation without allocation.
#include "scripting/jet_expression.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>
#include <numbers>
#include <string>
#include <vector>

#include "mech/errors.h"
#include "scripting/identifiers.h"
#include "scripting/lua_state.h"

// ---------------------------------------------------------------------------
// counting replacements of operator new (as tests/blocks/solver/no_allocation_test.cc)

namespace {

std::atomic<bool> g_counting{false};
std::atomic<long> g_new_calls{0};

void* Allocate(std::size_t size) {
  if (g_counting.load(std::memory_order_relaxed)) g_new_calls.fetch_add(1, std::memory_order_relaxed);
  return std::malloc(size == 0 ? 1 : size);
}

// Out of line, so that GCC does not pair the malloc inlined from operator new
// with this free and warn (-Wmismatched-new-delete).
[[gnu::noinline]] void Deallocate(void* p) noexcept { std::free(p); }

}  // namespace

void* operator new(std::size_t size) {
  if (void* p = Allocate(size)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) {
  if (void* p = Allocate(size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { Deallocate(p); }
void operator delete[](void* p) noexcept { Deallocate(p); }
void operator delete(void* p, std::size_t) noexcept { Deallocate(p); }
void operator delete[](void* p, std::size_t) noexcept { Deallocate(p); }

// ---------------------------------------------------------------------------

namespace mechflow::scripting {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

constexpr char kWhat[] = "m.xml:7: joint 'j'";

class TimeFunctionTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ids_.Add("r", "2", "f:1");
    ids_.Add("Omega", "1.5", "f:2");
    ids_.Add("phase", "0.25", "f:3");
    ids_.Add("alpha", "30", "f:4");
    ids_.Add("ampl", "0.1", "f:5");
    ids_.Add("om", "3", "f:6");
    ids_.Add("v_leader", "4", "f:7");
    ids_.Evaluate(lua_);
  }
  mech::Jet At(const std::string& text, double t) const { return JetExpression(text, ids_, "f:9").Evaluate(t); }
  double Value(const std::string& text) const { return At(text, 0.0).value; }
  // the InputError message of compiling `text`, or "no error"
  std::string ErrorOf(const std::string& text) const {
    try {
      JetExpression f(text, ids_, kWhat);
      return "no error";
    } catch (const InputError& e) {
      return e.what();
    }
  }
  // the message with the common prefix removed (checked to be there)
  std::string Detail(const std::string& text) const {
    const std::string message = ErrorOf(text);
    const std::string prefix = std::string(kWhat) + ": time function '" + text + "': ";
    EXPECT_THAT(message, StartsWith(prefix));
    return message.rfind(prefix, 0) == 0 ? message.substr(prefix.size()) : message;
  }

  LuaState lua_;
  IdentifierTable ids_;
};

// |actual - expected| <= tolerance * scale for value, rate and acceleration;
// `scale` is the size of the terms that make up each (so that a result near
// zero is not held to a relative tolerance it cannot meet).
void ExpectJet(const mech::Jet& actual, const mech::Jet& expected, double tolerance, const mech::Jet& scale) {
  EXPECT_NEAR(actual.value, expected.value, tolerance * scale.value);
  EXPECT_NEAR(actual.rate, expected.rate, tolerance * scale.rate);
  EXPECT_NEAR(actual.acceleration, expected.acceleration, tolerance * scale.acceleration);
}

// relative to the expected values themselves (plus 1e-300 so that exact zeros pass)
void ExpectJetRelative(const mech::Jet& actual, const mech::Jet& expected, double tolerance) {
  ExpectJet(
      actual, expected, tolerance,
      {std::abs(expected.value) + 1e-300, std::abs(expected.rate) + 1e-300, std::abs(expected.acceleration) + 1e-300});
}

// ---------------------------------------------------------------------------
// values and derivatives

TEST_F(TimeFunctionTest, CircularMotionHasExactDerivatives) {
  // r cos(wt + p): rate -r w sin, acceleration -r w^2 cos. The same few
  // roundings either way: 1e-14 of the amplitude r w^k (relative to the
  // amplitude, as cos and sin pass through zero).
  const double r = 2, w = 1.5, p = 0.25;
  const JetExpression f("r*cos(omega*t+phase)", ids_, kWhat);
  EXPECT_TRUE(f.depends_on_time());
  for (double t : {0.0, 0.3, 1.7, 5.0, -2.2, 123.4}) {
    const double a = w * t + p;
    ExpectJet(f.Evaluate(t), {r * std::cos(a), -r * w * std::sin(a), -r * w * w * std::cos(a)}, 1e-14,
              {r, r * w, r * w * w});
    ExpectJet(At("r*sin(omega*t+phase)", t), {r * std::sin(a), r * w * std::cos(a), -r * w * w * std::sin(a)}, 1e-14,
              {r, r * w, r * w * w});
  }
}

TEST_F(TimeFunctionTest, AProductWithAConstantZeroIsThatZero) {
  // the seed's base motion ampl*sin(2*pi*om*t), switched off by its amplitude
  for (const char* text : {"0*sin(2*pi*t)", "sin(2*pi*t)*(alpha-30)", "0*ln(t-1)"}) {
    const JetExpression f(text, ids_, kWhat);
    EXPECT_EQ(f.num_instructions(), 1) << text;
    EXPECT_TRUE(f.depends_on_time()) << text;  // its text names t
    const mech::Jet j = f.Evaluate(0.5);  // ln(t-1) is not evaluated there
    EXPECT_EQ(j.value, 0.0) << text;
    EXPECT_EQ(j.rate, 0.0) << text;
    EXPECT_EQ(j.acceleration, 0.0) << text;
  }
}

TEST_F(TimeFunctionTest, ExpressionsWithoutTAreConstantsWithZeroDerivatives) {
  const JetExpression f("alpha*pi/180", ids_, kWhat);
  EXPECT_FALSE(f.depends_on_time());
  EXPECT_EQ(f.num_instructions(), 1);  // folded at compilation
  for (double t : {0.0, 1.0, -3.5, 1e6}) {
    const mech::Jet j = f.Evaluate(t);
    EXPECT_EQ(j.value, 30 * std::numbers::pi / 180);  // the same operations in the same order: exact
    EXPECT_EQ(j.rate, 0.0);
    EXPECT_EQ(j.acceleration, 0.0);
  }
  EXPECT_EQ(EvaluateConstantExpression("alpha*pi/180", ids_, kWhat), 30 * std::numbers::pi / 180);
  EXPECT_EQ(EvaluateConstantExpression("sqr(r) + 1", ids_, kWhat), 5.0);
}

TEST_F(TimeFunctionTest, ConstantOperandsAreFoldedIntoTheProgram) {
  // push t, *omega, +phase, cos, *r
  const JetExpression f("r*cos(omega*t+phase)", ids_, kWhat);
  EXPECT_EQ(f.num_instructions(), 5);
  EXPECT_EQ(f.stack_depth(), 1);
  EXPECT_EQ(f.identifiers_used(), (std::vector<std::string>{"r", "omega", "phase"}));
  // constant sub-expressions anywhere fold to one number
  EXPECT_EQ(JetExpression("t*(2*pi*om/180 + sqr(ampl))", ids_, kWhat).num_instructions(), 2);
}

TEST_F(TimeFunctionTest, ProductQuotientChainAndPowerRules) {
  // hand-derived derivatives; a handful of roundings each: 1e-13 relative
  constexpr double kTol = 1e-13;
  for (double t : {0.7, 1.9}) {
    const double e = std::exp(-t), s3 = std::sin(3 * t), c3 = std::cos(3 * t);
    ExpectJetRelative(At("exp(-t)*sin(3*t)", t), {e * s3, e * (3 * c3 - s3), e * (-8 * s3 - 6 * c3)}, kTol);
    ExpectJetRelative(At("t^3", t), {t * t * t, 3 * t * t, 6 * t}, kTol);
    ExpectJetRelative(At("t^-2", t), {1 / (t * t), -2 / (t * t * t), 6 / (t * t * t * t)}, kTol);
    const double q = 1 + t * t;
    ExpectJetRelative(At("sqrt(1+t^2)", t), {std::sqrt(q), t / std::sqrt(q), std::pow(q, -1.5)}, kTol);
    ExpectJetRelative(At("ln(2+t)", t), {std::log(2 + t), 1 / (2 + t), -1 / ((2 + t) * (2 + t))}, kTol);
    ExpectJetRelative(At("log(2+t)", t), {std::log(2 + t), 1 / (2 + t), -1 / ((2 + t) * (2 + t))}, kTol);
    const double th = std::tanh(t);
    ExpectJetRelative(At("tanh(t)", t), {th, 1 - th * th, -2 * th * (1 - th * th)}, kTol);
    ExpectJetRelative(At("sinh(2*t)", t), {std::sinh(2 * t), 2 * std::cosh(2 * t), 4 * std::sinh(2 * t)}, kTol);
    ExpectJetRelative(At("cosh(2*t)", t), {std::cosh(2 * t), 2 * std::sinh(2 * t), 4 * std::cosh(2 * t)}, kTol);
    const double l2 = std::log(2.0), p2 = std::pow(2.0, t);
    ExpectJetRelative(At("2^t", t), {p2, l2 * p2, l2 * l2 * p2}, kTol);
    // t^t = exp(t ln t): rate t^t (ln t + 1), acceleration t^t ((ln t + 1)^2 + 1/t)
    const double tt = std::pow(t, t), g = std::log(t) + 1;
    ExpectJetRelative(At("t^t", t), {tt, tt * g, tt * (g * g + 1 / t)}, kTol);
    ExpectJetRelative(At("1/(1+t)", t), {1 / (1 + t), -1 / ((1 + t) * (1 + t)), 2 / std::pow(1 + t, 3)}, kTol);
    ExpectJetRelative(At("t/(1+t)", t), {t / (1 + t), 1 / ((1 + t) * (1 + t)), -2 / std::pow(1 + t, 3)}, kTol);
    ExpectJetRelative(At("sqr(sin(t))", t), {std::sin(t) * std::sin(t), std::sin(2 * t), 2 * std::cos(2 * t)}, kTol);
    const double sec2 = 1 / (std::cos(t / 2) * std::cos(t / 2));
    ExpectJetRelative(At("tan(t/2)", t), {std::tan(t / 2), sec2 / 2, sec2 * std::tan(t / 2) / 2}, kTol);
    const double u = t / 2, w = 1 / std::sqrt(1 - u * u);  // d/du asin = w, d2/du2 = u w^3
    ExpectJetRelative(At("asin(t/2)", t), {std::asin(u), w / 2, u * w * w * w / 4}, kTol);
    ExpectJetRelative(At("arccos(t/2)", t), {std::acos(u), -w / 2, -u * w * w * w / 4}, kTol);
    ExpectJetRelative(At("arctan(t)", t), {std::atan(t), 1 / q, -2 * t / (q * q)}, kTol);
    // atan(y, x) of a point on a circle is the angle itself: rate 1, acceleration 0
    ExpectJet(At("atan(sin(t), cos(t))", t), {t, 1, 0}, 1e-14, {1, 1, 1});  // a few ulp
    ExpectJetRelative(At("sign(t - 1)*t", t), {(t > 1 ? 1 : -1) * t, t > 1 ? 1.0 : -1.0, 0}, kTol);
  }
}

TEST_F(TimeFunctionTest, PowersAtZeroHaveNoSpuriousInfinities) {
  // n (n-1) 0^(n-2) would be 0*inf for n = 1; exact small numbers throughout
  ExpectJet(At("t^0", 0), {1, 0, 0}, 0, {1, 1, 1});
  ExpectJet(At("t^1", 0), {0, 1, 0}, 0, {1, 1, 1});
  ExpectJet(At("t^2", 0), {0, 0, 2}, 0, {1, 1, 1});
  ExpectJet(At("t^3", 0), {0, 0, 0}, 0, {1, 1, 1});
  ExpectJet(At("(2*t)^2", 0), {0, 0, 8}, 0, {1, 1, 1});
  ExpectJet(At("sqr(t - 1)", 1), {0, 0, 2}, 0, {1, 1, 1});
  EXPECT_THROW(At("t^0.5", 0), SimulationError);  // the rate is infinite there
}

TEST_F(TimeFunctionTest, PrescribedMotionsOfTheSeedModels) {
  // ampl sin(2 pi om t) and v_leader t; 1e-14 of the amplitudes
  const double k = 2 * std::numbers::pi * 3;
  for (double t : {0.0, 0.11, 2.5}) {
    ExpectJet(At("ampl*sin(2*pi*om*t)", t),
              {0.1 * std::sin(k * t), 0.1 * k * std::cos(k * t), -0.1 * k * k * std::sin(k * t)}, 1e-14,
              {0.1, 0.1 * k, 0.1 * k * k});
    ExpectJet(At("v_leader*t", t), {4 * t, 4, 0}, 1e-15, {4 * (1 + t), 4, 1});
  }
}

TEST_F(TimeFunctionTest, DerivativesAgreeWithDifferencesOfTheValues) {
  // An independent check of every rule at once: the rate against a
  // fourth-order central difference of the value, the acceleration against
  // one of the rate. Step 1e-3: truncation ~h^4 = 1e-12, rounding ~1e-16/h =
  // 1e-13, both times the size of the derivatives here (< 100): 1e-8 of
  // (1 + |exact|) leaves a wide margin and still catches any wrong term.
  const char* expressions[] = {
      "r*cos(omega*t+phase)*exp(-t/3) + sqrt(1+t^2)/(2+sin(t))",
      "t^t - 2^(t*t) + (1+t)^(1/3)",
      "atan(sin(2*t), 1+cos(t)/2) + arctan(t^2)",
      "asin(t/3)*acos(t/4) - tan(t/2)",
      "sinh(t/2)*cosh(t/3) - tanh(t)^2 + ln(1+t^2)^1.5",
      "max(t^2, 2*t) + min(sin(t), cos(t)) - abs(t-1.5) + sqr(t)/t^0.5",
      "-t^2/(1 + 8/t/2) - 3*-t + (t)^-1.5",
  };
  const double h = 1e-3;
  for (const char* text : expressions) {
    const JetExpression f(text, ids_, kWhat);
    for (double t : {0.37, 1.21, 2.9}) {
      const mech::Jet j = f.Evaluate(t);
      const auto d = [&](auto&& g) {
        return (-g(f.Evaluate(t + 2 * h)) + 8 * g(f.Evaluate(t + h)) - 8 * g(f.Evaluate(t - h)) +
                g(f.Evaluate(t - 2 * h))) /
               (12 * h);
      };
      const double rate = d([](const mech::Jet& x) { return x.value; });
      const double acceleration = d([](const mech::Jet& x) { return x.rate; });
      EXPECT_NEAR(j.rate, rate, 1e-8 * (1 + std::abs(rate))) << text << " at t = " << t;
      EXPECT_NEAR(j.acceleration, acceleration, 1e-8 * (1 + std::abs(acceleration))) << text << " at t = " << t;
    }
  }
}

TEST_F(TimeFunctionTest, BranchesTakeTheDerivativesOfTheActiveSide) {
  // exact: the chosen branch is passed through unchanged
  ExpectJet(At("min(t, 1)", 2), {1, 0, 0}, 0, {1, 1, 1});
  ExpectJet(At("min(t, 1)", 0.5), {0.5, 1, 0}, 0, {1, 1, 1});
  ExpectJet(At("max(t^2, 1)", 2), {4, 4, 2}, 0, {1, 1, 1});
  ExpectJet(At("max(3, t, t^2)", 1.5), {3, 0, 0}, 0, {1, 1, 1});
  ExpectJet(At("abs(t-1)", 0.5), {0.5, -1, 0}, 0, {1, 1, 1});
  ExpectJet(At("abs(t^2-4)", 1), {3, -2, -2}, 0, {1, 1, 1});
  ExpectJet(At("sign(t-1)", 0.5), {-1, 0, 0}, 0, {1, 1, 1});
  ExpectJet(At("sign(t)", 0), {0, 0, 0}, 0, {1, 1, 1});
  // at a tie, the side that is active just after t
  ExpectJet(At("abs(t)", 0), {0, 1, 0}, 0, {1, 1, 1});
  ExpectJet(At("abs(-t)", 0), {0, 1, 0}, 0, {1, 1, 1});
  ExpectJet(At("abs(t^2)", 0), {0, 0, 2}, 0, {1, 1, 1});
  ExpectJet(At("min(t, 0)", 0), {0, 0, 0}, 0, {1, 1, 1});
  ExpectJet(At("max(t, 0)", 0), {0, 1, 0}, 0, {1, 1, 1});
  ExpectJet(At("min(t, t^2)", 0), {0, 0, 2}, 0, {1, 1, 1});  // t^2 < t just after 0
  ExpectJet(At("max(t, t^2)", 1), {1, 2, 2}, 0, {1, 1, 1});  // t^2 > t just after 1
}

// ---------------------------------------------------------------------------
// grammar

TEST_F(TimeFunctionTest, PrecedenceFollowsLua) {
  EXPECT_EQ(Value("-2^2"), -4);
  EXPECT_EQ(Value("2^3^2"), 512);
  EXPECT_EQ(Value("1-2-3"), -4);
  EXPECT_EQ(Value("8/4/2"), 1);
  EXPECT_EQ(Value("2*-3"), -6);
  EXPECT_EQ(Value("2^-1"), 0.5);
  EXPECT_EQ(Value("-2^-2"), -0.25);
  EXPECT_EQ(Value("+2 - -3"), 5);
  EXPECT_EQ(Value("1+2*3^2"), 19);
  EXPECT_EQ(Value("(1+2)*3"), 9);
  EXPECT_EQ(At("-t^2", 3).value, -9);
  EXPECT_EQ(At("2^t^2", 3).value, 512);
  EXPECT_EQ(Value("9.8696044E+5"), 986960.44);
  EXPECT_EQ(Value(".5"), 0.5);
  EXPECT_EQ(Value("2."), 2);
  EXPECT_EQ(Value("1e-3"), 0.001);
  EXPECT_EQ(Value("0x10"), 16);
  EXPECT_EQ(Value("0x1p-3"), 0.125);
  EXPECT_EQ(Value(" \t( 1 +\n 2 ) "), 3);
}

TEST_F(TimeFunctionTest, ValuesAgreeWithTheLuaEvaluationOfTheSameText) {
  // The grammar is a subset of the Lua expressions that identifiers and force
  // laws use; t-free texts must give the same numbers. Equal to 4 ulp: Lua's
  // one-argument atan is atan2(x, 1) where this uses atan(x); all else is the
  // same operations in the same order.
  const char* texts[] = {
      "-2^2",
      "2^3^2",
      "1-2-3",
      "8/4/2",
      "2*-3",
      "2^-1",
      "-2^-2",
      "- -2",
      "9.8696044E+5",
      ".5",
      "2.",
      "0x10",
      "0x1p-3",
      "1e-3",
      "alpha*pi/180",
      "r*cos(omega*0.3+phase)",
      "R*cos(OMEGA*0.3+Phase)",
      "sqr(3)",
      "sign(-2)",
      "abs(-2.5)",
      "min(3, 1, 2)",
      "max(3, 1, 2)",
      "atan(1, 2)",
      "arctan(0.5)",
      "ln(2)",
      "log(10)",
      "sqrt(2)",
      "exp(1)",
      "sinh(0.5)+cosh(0.5)*tanh(0.5)",
      "asin(0.5)+acos(0.5)",
      "arcsin(0.1)*arccos(0.2)",
      "tan(1)",
      "2^0.5",
      "ampl*sin(2*pi*om*0.1)",
      "(1+2)*3/(4-5)^2",
      "v_leader/7",
  };
  for (const char* text : texts) EXPECT_DOUBLE_EQ(Value(text), ids_.EvaluateExpression(lua_, text, "lua")) << text;
}

TEST_F(TimeFunctionTest, NamesAreCaseInsensitive) {
  const double t = 0.8;
  const mech::Jet a = At("r*cos(omega*t+phase)", t);
  for (const char* text : {"R*COS(OMEGA*T+PHASE)", "r*Cos(Omega*t+Phase)", "R*cos(oMeGa*T + pHaSe)"}) {
    const mech::Jet b = At(text, t);
    EXPECT_EQ(a.value, b.value) << text;
    EXPECT_EQ(a.rate, b.rate) << text;
    EXPECT_EQ(a.acceleration, b.acceleration) << text;
  }
  EXPECT_EQ(Value("PI"), std::numbers::pi);
  EXPECT_EQ(JetExpression("OMEGA*T", ids_, kWhat).identifiers_used(), std::vector<std::string>{"omega"});
}

// ---------------------------------------------------------------------------
// errors

TEST_F(TimeFunctionTest, UnknownNamesAreInputErrorsWithSuggestions) {
  EXPECT_EQ(ErrorOf("omegaa*t"),
            "m.xml:7: joint 'j': time function 'omegaa*t': unknown name 'omegaa' at column 1 "
            "(did you mean 'omega'?); expected t, pi or an identifier");
  EXPECT_EQ(Detail("r*Phse + t"),
            "unknown name 'Phse' at column 3 (did you mean 'phase'?); expected t, pi or an identifier");
  EXPECT_EQ(Detail("q*t"), "unknown name 'q' at column 1; expected t, pi or an identifier");
  EXPECT_EQ(Detail("x + t"),
            "'x' at column 1: x and v are arguments of force laws; a time function depends on t alone");
  EXPECT_EQ(Detail("sine(t)"),
            "unknown function 'sine' at column 1 (did you mean 'sin'?); expected one of sin, cos, tan, asin, acos, "
            "atan, arcsin, arccos, arctan, sinh, cosh, tanh, exp, ln, log, sqrt, sqr, abs, sign, min, max");
  EXPECT_EQ(Detail("omega(t)"), "'omega' at column 1 is not a function; write '*' for a product");
  EXPECT_EQ(Detail("2*sin"), "the function 'sin' at column 3 needs its arguments in parentheses");
  EXPECT_EQ(Detail("floor(t)"), "'floor' at column 1 is not allowed in a time function: its jumps have no derivative");
  EXPECT_EQ(Detail("math.sin(t)"),
            "'math.' at column 1 is Lua field access, which time functions do not have; "
            "write 'sin' alone");
  EXPECT_EQ(Detail("2*math.pi*t"),
            "'math.' at column 3 is Lua field access, which time functions do not have; "
            "write 'pi' alone");
  EXPECT_EQ(Detail("os.time()"), "'os.' at column 1 is Lua field access, which time functions do not have");
}

TEST_F(TimeFunctionTest, LuaOnlySyntaxIsAnInputError) {
  const std::string after = "expected an operator (+ - * / ^) or the end of the expression, found ";
  EXPECT_EQ(Detail("t .. 1"),
            after + "'..' at column 3; '..' joins strings in Lua; time functions have only + - * / ^");
  EXPECT_EQ(Detail("t > 1"), after + "'>' at column 3; time functions have no comparisons");
  EXPECT_EQ(Detail("t == 1"), after + "'==' at column 3; time functions have no comparisons");
  EXPECT_EQ(Detail("t ~= 1"), after + "'~=' at column 3; time functions have no comparisons");
  EXPECT_EQ(Detail("t and 1"),
            after + "'and' at column 3; Lua keywords (and, or, not, nil, ...) are not part of a time function");
  EXPECT_EQ(Detail("not t"),
            "expected a number, a name, '(' or a sign, found 'not' at column 1; Lua keywords "
            "(and, or, not, nil, ...) are not part of a time function");
  EXPECT_EQ(Detail("t % 2"), after + "'%' at column 3; time functions have only the operators + - * / ^");
  EXPECT_EQ(Detail("t // 2"), after + "'//' at column 3; time functions have only the operators + - * / ^");
  EXPECT_EQ(Detail("t--1"), after +
                                "'--' at column 2; in Lua '--' starts a comment; write '- -' or '+' to negate "
                                "twice");
  EXPECT_EQ(Detail("'1' + t"),
            "expected a number, a name, '(' or a sign, found a string at column 1; time "
            "functions have no strings");
  EXPECT_EQ(Detail("t = 1"), after + "'=' at column 3; a time function is an expression, not an assignment");
  EXPECT_EQ(Detail("#t"), "expected a number, a name, '(' or a sign, found '#' at column 1");
  EXPECT_EQ(Detail("t $ 1"), after + "'$' at column 3");
}

TEST_F(TimeFunctionTest, MalformedExpressionsAreInputErrors) {
  EXPECT_EQ(Detail("2t"), "malformed number '2t' at column 1 (write '*' for a product, as in '2*t')");
  EXPECT_EQ(Detail("1.2.3"), "malformed number '1.2.3' at column 1 (write '*' for a product, as in '2*t')");
  EXPECT_EQ(Detail("0x"), "malformed number '0x' at column 1 (write '*' for a product, as in '2*t')");
  EXPECT_EQ(Detail("1e999*t"), "the number '1e999' at column 1 is out of range");
  EXPECT_EQ(Detail("2 t"),
            "expected an operator (+ - * / ^) or the end of the expression, found 't' at column 3; "
            "write '*' for a product");
  EXPECT_EQ(Detail("2(t+1)"),
            "expected an operator (+ - * / ^) or the end of the expression, found '(' at column "
            "2; write '*' for a product");
  EXPECT_EQ(Detail("(t+1"),
            "expected an operator (+ - * / ^) or ')' closing the '(' at column 1, found the end of "
            "the expression");
  EXPECT_EQ(Detail("t+1)"), "expected an operator (+ - * / ^) or the end of the expression, found ')' at column 4");
  EXPECT_EQ(Detail("t*"), "expected a number, a name, '(' or a sign, found the end of the expression");
  EXPECT_EQ(Detail(""), "expected a number, a name, '(' or a sign, found the end of the expression");
  EXPECT_EQ(Detail("sin(t;"),
            "expected an operator (+ - * / ^), ',' or ')' closing the arguments of 'sin' at "
            "column 4, found ';' at column 6");
  EXPECT_EQ(Detail("sin(t, 1)"), "'sin' at column 1 takes 1 argument, found 2");
  EXPECT_EQ(Detail("cos()"), "'cos' at column 1 takes 1 argument, found 0");
  EXPECT_EQ(Detail("min(t)"), "'min' at column 1 takes 2 or more arguments, found 1");
  EXPECT_EQ(Detail("atan(t, 1, 2)"), "'atan' at column 1 takes 1 or 2 arguments, found 3");
  EXPECT_EQ(Detail("ln(t, 2)"), "'ln' at column 1 takes 1 argument, found 2 (for another base write ln(x)/ln(b))");
}

TEST_F(TimeFunctionTest, LimitsAndNonFiniteConstantsAreInputErrors) {
  EXPECT_EQ(Detail("ln(alpha-30)*t"), "'ln(alpha-30)' is -inf for the identifiers' values (it does not depend on t)");
  EXPECT_EQ(Detail("t + (1/0)"), "'1/0' is inf for the identifiers' values (it does not depend on t)");
  EXPECT_EQ(Detail("sqrt(-r) + t"), "'sqrt(-r)' is nan for the identifiers' values (it does not depend on t)");

  const std::string deep = std::string(150, '(') + "t" + std::string(150, ')');
  EXPECT_EQ(Detail(deep), "nested more than 100 deep at column 101");
  // each level needs a stack slot: t*(t+(t*(t+ ... ))) with 40 t's
  std::string wide = "t";
  for (int i = 0; i < 40; ++i) wide = std::string("t") + (i % 2 ? "*(" : "+(") + wide + ")";
  EXPECT_THAT(Detail(wide), StartsWith("needs 41 evaluation stack slots, more than the 32 available"));
  std::string ok = "t";
  for (int i = 0; i < 30; ++i) ok = std::string("t") + (i % 2 ? "*(" : "+(") + ok + ")";
  EXPECT_EQ(JetExpression(ok, ids_, kWhat).stack_depth(), 31);

  std::string longest = "t";
  while (longest.size() + 2 <= 2000) longest += "+t";
  EXPECT_EQ(JetExpression(longest, ids_, kWhat).Evaluate(1).value, 1000);
  EXPECT_EQ(ErrorOf(longest + "+t"),
            "m.xml:7: joint 'j': time function of 2001 characters: longer than 2000; simplify it or use identifiers");

  EXPECT_THROW(EvaluateConstantExpression("2*t", ids_, kWhat), InputError);
  try {
    EvaluateConstantExpression("2*t", ids_, kWhat);
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "m.xml:7: joint 'j': '2*t' depends on t; expected an expression of numbers and identifiers");
  }
}

TEST_F(TimeFunctionTest, EveryErrorIsAnInputErrorStartingWithWhat) {
  for (const char* text : {"omegaa*t",       "x",      "sine(t)",      "omega(t)", "sin",   "floor(t)",
                           "math.sin(t)",    "t..1",   "t<1",          "t and 1",  "not t", "t%2",
                           "t//2",           "t--1",   "\"a\"",        "t=1",      "2t",    "1.2.3",
                           "1e999",          "2 t",    "(t",           "t)",       "t*",    "",
                           "sin(t,1)",       "min(t)", "ln(alpha-30)", "{t}",      "t[1]",  "t:f()",
                           "function() end", "@"}) {
    try {
      JetExpression f(text, ids_, kWhat);
      ADD_FAILURE() << "no error for '" << text << "'";
    } catch (const InputError& e) {
      EXPECT_THAT(e.what(), StartsWith(std::string(kWhat) + ": time function '" + text + "': ")) << text;
    }
  }
}

TEST_F(TimeFunctionTest, NonFiniteResultIsASimulationError) {
  const JetExpression f("ln(t-1)", ids_, "m.xml:3");
  EXPECT_NO_THROW(f.Evaluate(2.0));
  EXPECT_THROW(f.Evaluate(0.0), SimulationError);
  const auto message = [](const JetExpression& g, double t) -> std::string {
    try {
      g.Evaluate(t);
      return "no error";
    } catch (const SimulationError& e) {
      return e.what();
    }
  };
  EXPECT_EQ(message(f, 0.0),
            "m.xml:3: time function 'ln(t-1)' is not finite at t = 0 (value nan, rate -1, acceleration -1)");
  // the first part that went non-finite is named
  EXPECT_EQ(message(JetExpression("2 + 3*ln(t-1)", ids_, "m.xml:3"), 0.5),
            "m.xml:3: time function '2 + 3*ln(t-1)' is not finite at t = 0.5: its part 'ln(t-1)' is not "
            "(value nan, rate -2, acceleration -4)");
  // a rate or acceleration that is not finite counts too: sqrt at 0
  // (acceleration: -inf + inf*0)
  EXPECT_EQ(message(JetExpression("sqrt(t)", ids_, "m.xml:3"), 0.0),
            "m.xml:3: time function 'sqrt(t)' is not finite at t = 0 (value 0, rate inf, acceleration nan)");
  // min and max do not hide a NaN
  EXPECT_THAT(message(JetExpression("min(ln(t-1), 1)", ids_, "m.xml:3"), 0.0),
              HasSubstr("its part 'ln(t-1)' is not"));
  // general powers need a positive base
  EXPECT_THAT(message(JetExpression("(t-1)^t", ids_, "m.xml:3"), 0.5), HasSubstr("is not finite at t = 0.5"));
  EXPECT_THROW(JetExpression("1/t", ids_, "m.xml:3").Evaluate(0.0), SimulationError);
}

// ---------------------------------------------------------------------------
// evaluation cost

TEST_F(TimeFunctionTest, EvaluationAllocatesNothing) {
  const JetExpression f("r*cos(omega*t+phase) + exp(-t)*t^3/(1+t^2) + min(t, 1) + 2^t + atan(t, 2)", ids_,
                               kWhat);
  double sum = 0;
  g_new_calls = 0;
  g_counting = true;
  for (int i = 0; i < 1000; ++i) sum += f.Evaluate(0.001 * i).acceleration;
  g_counting = false;
  EXPECT_EQ(g_new_calls.load(), 0);
  EXPECT_TRUE(std::isfinite(sum));
}

}  // namespace
}  // namespace mechflow::scripting
