// Time functions with exact derivatives, against hand-derived closed forms.
#include "scripting/time_function.h"

#include <cmath>

#include <gtest/gtest.h>

#include "mech/errors.h"
#include "scripting/identifiers.h"
#include "scripting/lua_state.h"

namespace mechflow::scripting {
namespace {

class TimeFunctionTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ids_.Add("r", "2", "f:1");
    ids_.Add("Omega", "1.5", "f:2");
    ids_.Add("phase", "0.25", "f:3");
    ids_.Add("alpha", "30", "f:4");
    ids_.Evaluate(lua_);
  }
  mech::Jet At(const std::string& text, double t) { return CompiledTimeFunction(text, ids_, "f:9").Evaluate(t); }
  std::string ErrorOf(const std::string& text) {
    try {
      CompiledTimeFunction f(text, ids_, "m.xml:7: joint 'j'");
      return "no error";
    } catch (const InputError& e) {
      return e.what();
    }
  }
  LuaState lua_;
  IdentifierTable ids_;
};

void ExpectJet(const mech::Jet& j, double v, double d1, double d2, double tol = 1e-13) {
  EXPECT_NEAR(j.value, v, tol * (1 + std::abs(v)));
  EXPECT_NEAR(j.rate, d1, tol * (1 + std::abs(d1)));
  EXPECT_NEAR(j.acceleration, d2, tol * (1 + std::abs(d2)));
}

TEST_F(TimeFunctionTest, CircleOfRoundHasExactDerivatives) {
  for (double t : {0.0, 0.3, 1.7, 5.0}) {
    const double a = 1.5 * t + 0.25;
    ExpectJet(At("r*cos(omega*t+phase)", t), 2 * std::cos(a), -3 * std::sin(a), -4.5 * std::cos(a));
    ExpectJet(At("r*sin(OMEGA*t+Phase)", t), 2 * std::sin(a), 3 * std::cos(a), -4.5 * std::sin(a));
  }
}

TEST_F(TimeFunctionTest, ConstantsHaveNoDerivatives) {
  CompiledTimeFunction f("alpha*pi/180", ids_, "f:9");
  EXPECT_FALSE(f.depends_on_time());
  ExpectJet(f.Evaluate(3.0), M_PI / 6, 0, 0);
}

TEST_F(TimeFunctionTest, ProductQuotientChainAndPowerRules) {
  const double t = 0.7;
  ExpectJet(At("exp(-t)*sin(3*t)", t), std::exp(-t) * std::sin(3 * t),
            std::exp(-t) * (3 * std::cos(3 * t) - std::sin(3 * t)),
            std::exp(-t) * (-8 * std::sin(3 * t) - 6 * std::cos(3 * t)));
  ExpectJet(At("t^3", t), t * t * t, 3 * t * t, 6 * t);
  ExpectJet(At("sqrt(1+t^2)", t), std::sqrt(1 + t * t), t / std::sqrt(1 + t * t), std::pow(1 + t * t, -1.5));
  ExpectJet(At("ln(2+t)", t), std::log(2 + t), 1 / (2 + t), -1 / ((2 + t) * (2 + t)));
  ExpectJet(At("2^t", t), std::pow(2, t), std::log(2) * std::pow(2, t), std::log(2) * std::log(2) * std::pow(2, t));
  ExpectJet(At("1/(1+t)", t), 1 / (1 + t), -1 / ((1 + t) * (1 + t)), 2 / std::pow(1 + t, 3));
  const double th = std::tanh(t);
  ExpectJet(At("tanh(t)", t), th, 1 - th * th, -2 * th * (1 - th * th));
  ExpectJet(At("sqr(sin(t))", t), std::sin(t) * std::sin(t), std::sin(2 * t), 2 * std::cos(2 * t));
  ExpectJet(At("max(t, 1) + min(t, 0.5)", t), 1 + 0.5, 0, 0);
}

TEST_F(TimeFunctionTest, PrecedenceFollowsLua) {
  EXPECT_EQ(At("-2^2", 0).value, -4);
  EXPECT_EQ(At("2^3^2", 0).value, 512);
  EXPECT_EQ(At("1-2-3", 0).value, -4);
  EXPECT_EQ(At("8/4/2", 0).value, 1);
  EXPECT_EQ(At("2*-3", 0).value, -6);
  EXPECT_EQ(At("9.8696044E+5", 0).value, 986960.44);
  EXPECT_EQ(At(".5", 0).value, 0.5);
}

TEST_F(TimeFunctionTest, BadExpressionsNameWhereAndWhat) {
  EXPECT_NE(ErrorOf("omegaa*t").find("m.xml:7: joint 'j': time function 'omegaa*t': unknown identifier 'omegaa' "
                                     "(did you mean 'omega'?)"),
            std::string::npos)
      << ErrorOf("omegaa*t");
  EXPECT_NE(ErrorOf("math.sin(t)").find("field access"), std::string::npos);
  EXPECT_NE(ErrorOf("t .. 1").find("unexpected '.'"), std::string::npos);
  EXPECT_NE(ErrorOf("t > 1").find("unexpected '>'"), std::string::npos);
  EXPECT_NE(ErrorOf("foo(t)").find("unknown function 'foo'"), std::string::npos);
  EXPECT_NE(ErrorOf("min(t)").find("min takes 2 arguments"), std::string::npos);
  EXPECT_NE(ErrorOf("(t").find("')' missing"), std::string::npos);
  EXPECT_NE(ErrorOf("t*").find("ends too early"), std::string::npos);
}

TEST_F(TimeFunctionTest, NonFiniteResultIsASimulationError) {
  CompiledTimeFunction f("ln(t-1)", ids_, "m.xml:3");
  EXPECT_THROW(f.Evaluate(0.0), SimulationError);
}

}  // namespace
}  // namespace mechflow::scripting
