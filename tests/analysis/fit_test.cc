// Fitting parameters to measured data: the damped oscillator's frequency
// and damping ratio recovered from its closed-form motion, exactly without
// noise, and within their standard errors with seeded noise, the standard
// errors checked against a Monte Carlo of the noise; the guards that refuse
// a fit before it runs; a run that fails during a fit.
#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "analysis/fit/fit.h"
#include "diagrams/xml_reader.h"
#include "mech/errors.h"
#include "run/model.h"
#include "tests/numbers.h"

namespace mechflow::analysis::fit {
namespace fit_test {

using ::testing::HasSubstr;
using mechflow::testing::kPi;

std::string Example(const std::string& name) { return std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/" + name; }

// x(t) of m x'' = -c x - d v from x0, v0 = 0: frequency f, damping ratio beta.
double Displacement(double t, double f, double beta, double x0) {
  const double w = 2 * kPi * f, wd = w * std::sqrt(1 - beta * beta);
  return x0 * std::exp(-beta * w * t) * (std::cos(wd * t) + beta * w / wd * std::sin(wd * t));
}

// The damped oscillator measured at 0.05 s steps for 4 s, x with noise of `sigma`.
Experiment Measured(double f, double beta, double sigma, unsigned seed) {
  std::mt19937 random(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  Experiment e;
  e.file = "measured.csv";
  e.measured.resize(1);
  for (int i = 1; i <= 80; ++i) {
    e.times.push_back(0.05 * i);
    e.lines.push_back(i + 1);
    e.measured[0].push_back(Displacement(0.05 * i, f, beta, 0.5) + (sigma > 0 ? noise(random) : 0.0));
  }
  return e;
}

fit::Setup Oscillator(std::vector<Experiment> experiments, double weight = 1.0) {
  fit::Setup s;
  s.diagram = Example("damped_oscillator_blocks.xml");
  s.description = diagrams::ReadDiagramFile(s.diagram);
  fit::Match match;
  match.signal = "x.y";
  match.column = "x";
  match.weight = weight;
  s.matches = {match};
  s.experiments = std::move(experiments);
  s.parameters = {ParseFree("f=0.5:2"), ParseFree("beta=0.01:0.5:log")};
  s.threads = 2;
  return s;
}

TEST(Fit, ParsesFreeParametersAndMatches) {
  const FreeParameter p = ParseFree("c=1e3:1e6:log");
  EXPECT_EQ(p.name, "c");
  EXPECT_TRUE(p.log);
  EXPECT_NEAR(p.FromUnit(0.5), std::sqrt(1e9), 1e-6);
  EXPECT_NEAR(p.ToUnit(1e4), 1.0 / 3.0, 1e-14);
  EXPECT_THROW(ParseFree("c=1e3"), InputError);
  EXPECT_THROW(ParseFree("c=0:1:log"), InputError);
  EXPECT_THROW(ParseFree("c=2:1"), InputError);
  const Match m = ParseMatch("m.x=x_meas:50");
  EXPECT_EQ(m.signal, "m.x");
  EXPECT_EQ(m.column, "x_meas");
  EXPECT_EQ(m.weight, 50);
  EXPECT_THROW(ParseMatch("m.x=x:0"), InputError);
  EXPECT_THROW(ParseMatch("m.x"), InputError);
}

// No noise: the closed form's parameters come back to the solver's accuracy.
TEST(Fit, RecoversOscillatorExactly) {
  Fitter fitter(Oscillator({Measured(1.2, 0.15, 0.0, 1)}));
  fitter.Probe();
  const FitResult r = fitter.Run({});
  EXPECT_TRUE(r.optimiser.converged) << r.optimiser.report;
  EXPECT_NEAR(r.values[0], 1.2, 1e-6);
  EXPECT_NEAR(r.values[1], 0.15, 1e-6);
  EXPECT_LT(r.cost_after, 1e-12);
  EXPECT_GT(r.cost_before, 1.0);
  EXPECT_TRUE(r.failures.empty());
}

// Seeded noise: within two standard errors, and the standard errors agree
// with the spread of the estimates over 40 noise seeds within 30 %.
TEST(Fit, StandardErrorsAgreeWithMonteCarlo) {
  const double sigma = 0.01;
  std::vector<std::vector<double>> estimates(2);
  std::vector<double> reported;
  for (unsigned seed = 1; seed <= 40; ++seed) {
    Fitter fitter(Oscillator({Measured(1.2, 0.15, sigma, seed)}, 1.0 / sigma));
    const FitResult r = fitter.Run({});
    if (seed == 1) {
      reported = r.statistics.standard_error;
      EXPECT_NEAR(r.values[0], 1.2, 2 * reported[0]);
      EXPECT_NEAR(r.values[1], 0.15, 2 * reported[1]);
      EXPECT_NEAR(r.statistics.variance, 1.0, 0.35);  // weights 1/sigma: unit variance
      EXPECT_TRUE(r.statistics.indistinct.empty());
    }
    for (int j = 0; j < 2; ++j) estimates[j].push_back(r.values[j]);
  }
  for (int j = 0; j < 2; ++j) {
    double mean = 0, square = 0;
    for (const double v : estimates[j]) mean += v / 40;
    for (const double v : estimates[j]) square += (v - mean) * (v - mean) / 39;
    EXPECT_NEAR(std::sqrt(square), reported[j], 0.3 * reported[j]) << "parameter " << j;
  }
}

// Two experiments (two starting displacements) fitted together.
TEST(Fit, FitsExperimentsTogether) {
  Experiment a = Measured(0.8, 0.05, 0.0, 1), b = Measured(0.8, 0.05, 0.0, 1);
  for (std::size_t i = 0; i < b.times.size(); ++i) b.measured[0][i] = Displacement(b.times[i], 0.8, 0.05, 0.2);
  b.overrides = {{"x0", 0.2}};
  Fitter fitter(Oscillator({a, b}));
  const FitResult r = fitter.Run({});
  EXPECT_NEAR(r.values[0], 0.8, 1e-6);
  EXPECT_NEAR(r.values[1], 0.05, 1e-6);
  EXPECT_EQ(r.residuals, 160);
}

TEST(Fit, DerivativeFreeRecoversOscillator) {
  Fitter fitter(Oscillator({Measured(1.2, 0.15, 0.0, 1)}));
  FitOptions options;
  options.method = Method::kDerivativeFree;
  const FitResult r = fitter.Run(options);
  EXPECT_NEAR(r.values[0], 1.2, 1e-4);
  EXPECT_NEAR(r.values[1], 0.15, 1e-4);
  EXPECT_LT(r.cost_after, 1e-6);
}

TEST(Fit, RefusesParameterWithoutEffect) {
  fit::Setup s = Oscillator({Measured(1.2, 0.15, 0.0, 1)});
  s.parameters.push_back(ParseFree("m=500:2000"));  // c and d follow m: the motion does not
  Fitter fitter(std::move(s));
  try {
    fitter.Probe();
    FAIL() << "no refusal";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("m has no effect on x.y"));
  }
}

TEST(Fit, MovesStartOnBoundInside) {
  fit::Setup s = Oscillator({Measured(1.2, 0.15, 0.0, 1)});
  s.parameters[0] = ParseFree("f=1:2");  // the diagram's f is 1
  Fitter fitter(std::move(s));
  ASSERT_EQ(fitter.notes().size(), 1u);
  EXPECT_THAT(fitter.notes()[0], HasSubstr("the start of f, 1, is on a bound; moved inside to 1.01"));
  EXPECT_NEAR(fitter.Run({}).values[0], 1.2, 1e-6);
}

// An identifier in N/mm starts from its value in N/mm, as --set and the bounds
// give it, not from its SI value.
TEST(Fit, StartsInTheUnitOfTheDefinition) {
  fit::Setup s = Oscillator({Measured(1.2, 0.15, 0.0, 1)});
  s.description = diagrams::ReadDiagramText(R"(<diagram name="units">
  <identifiers><identifier name="k" value="5" unit="N/mm"/><identifier name="m" value="1000" unit="kg"/></identifiers>
  <blocks><block type="integrator" name="x" initial="1"/><block type="gain" name="g" k="-k/m"/></blocks>
  <connections><connect from="x.y" to="g.u"/><connect from="g.y" to="x.u"/></connections>
  <solver t_end="10" rtol="1e-10" atol="1e-12"/></diagram>)", "units.xml");
  for (std::size_t i = 0; i < s.experiments[0].times.size(); ++i)
    s.experiments[0].measured[0][i] = std::exp(-4.0 * s.experiments[0].times[i]);  // k = 4 N/mm
  s.parameters = {ParseFree("k=1:10")};
  Fitter fitter(std::move(s));
  EXPECT_TRUE(fitter.notes().empty());
  const FitResult r = fitter.Run({});
  EXPECT_DOUBLE_EQ(r.start[0], 5.0);
  EXPECT_NEAR(r.values[0], 4.0, 1e-6);
}

TEST(Fit, RefusesBadSetups) {
  fit::Setup outside = Oscillator({Measured(1.2, 0.15, 0.0, 1)});
  outside.parameters[0] = ParseFree("f=2:3");
  EXPECT_THROW(Fitter{std::move(outside)}, InputError);
  fit::Setup derived = Oscillator({Measured(1.2, 0.15, 0.0, 1)});
  derived.parameters[0] = ParseFree("c=1:100");
  EXPECT_THROW(Fitter{std::move(derived)}, InputError);
  fit::Setup late = Oscillator({Measured(1.2, 0.15, 0.0, 1)});
  late.experiments[0].times.back() = 20;  // the run ends at 10 s
  late.experiments[0].lines.back() = 81;
  try {
    Fitter fitter(std::move(late));
    FAIL() << "no refusal";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("measured.csv:81: time 20 is outside the run (0 to 10 s)"));
  }
  fit::Setup port = Oscillator({Measured(1.2, 0.15, 0.0, 1)});
  port.matches[0].signal = "x.z";
  EXPECT_THROW(Fitter{std::move(port)}, InputError);
}

// The product of two parameters is all the data can see.
TEST(Fit, NamesParametersThatCannotBeToldApart) {
  fit::Setup s = Oscillator({Measured(1.2, 0.15, 0.0, 1)});
  s.description = diagrams::ReadDiagramText(R"(<diagram name="product">
  <identifiers><identifier name="a" value="2"/><identifier name="b" value="3"/></identifiers>
  <blocks><block type="integrator" name="x" initial="1"/><block type="gain" name="k" k="-a*b"/></blocks>
  <connections><connect from="x.y" to="k.u"/><connect from="k.y" to="x.u"/></connections>
  <solver t_end="10" rtol="1e-10" atol="1e-12"/></diagram>)", "product.xml");
  for (std::size_t i = 0; i < s.experiments[0].times.size(); ++i)
    s.experiments[0].measured[0][i] = std::exp(-5.0 * s.experiments[0].times[i]);
  s.parameters = {ParseFree("a=1:4"), ParseFree("b=1:4")};
  Fitter fitter(std::move(s));
  const FitResult r = fitter.Run({});
  EXPECT_NEAR(r.values[0] * r.values[1], 5.0, 1e-5);
  ASSERT_EQ(r.statistics.indistinct.size(), 1u);
  EXPECT_THAT(r.statistics.indistinct[0], ::testing::ElementsAre("a", "b"));
  EXPECT_TRUE(std::isnan(r.statistics.standard_error[0]));
}

// A control script that raises an error past t = 1 s when a > 3: the
// instants it does not reach are large residuals and a message.
TEST(Fit, RunThatFailsIsLargeResidual) {
  fit::Setup s = Oscillator({Measured(1.2, 0.15, 0.0, 1)});
  s.description = diagrams::ReadDiagramText(R"(<diagram name="fails">
  <identifiers><identifier name="a" value="2"/></identifiers>
  <blocks><block type="integrator" name="x" initial="0.5"/><block type="gain" name="k" k="-a"/></blocks>
  <connections><connect from="x.y" to="k.u"/><connect from="k.y" to="x.u"/></connections>
  <script>function step(sim) if sim.t > 1 and a > 3 then error("a is too large") end end</script>
  <solver t_end="10" rtol="1e-10" atol="1e-12"/></diagram>)", "fails.xml");
  s.parameters = {ParseFree("a=1:4")};
  const Evaluation good = Score(s, {2.5});
  EXPECT_TRUE(good.failures.empty());
  const Evaluation bad = Score(s, {3.5});
  ASSERT_EQ(bad.failures.size(), 1u);
  EXPECT_THAT(bad.failures[0], HasSubstr("the run for measured.csv at a=3.5 failed at t = 1.05 s"));
  EXPECT_THAT(bad.failures[0], HasSubstr("a is too large"));
  ASSERT_EQ(bad.residuals.size(), 80u);
  EXPECT_NEAR(bad.residuals[0], std::exp(-3.5 * 0.05) * 0.5 - s.experiments[0].measured[0][0], 1e-8);
  double largest = 0;
  for (const double v : s.experiments[0].measured[0]) largest = std::max(largest, std::abs(v));
  EXPECT_DOUBLE_EQ(bad.residuals[79], 10 * largest);  // ten times the largest measured value
  // the fit goes on past such runs: the data are x0 e^(-2.9 t)
  for (std::size_t i = 0; i < s.experiments[0].times.size(); ++i)
    s.experiments[0].measured[0][i] = 0.5 * std::exp(-2.9 * s.experiments[0].times[i]);
  Fitter fitter(std::move(s));
  const FitResult r = fitter.Run({});
  EXPECT_NEAR(r.values[0], 2.9, 1e-6);
}

// A point that breaks a constraint is not run: large residuals, a message.
TEST(Fit, ConstraintKeepsPointsFromRunning) {
  fit::Setup s = Oscillator({Measured(1.2, 0.15, 0.0, 1)});
  s.constraints = {ParseConstraint("beta >= f", s.parameters)};  // beta <= 0.5 < f: never kept
  EXPECT_EQ(s.constraints[0].lower, 0);
  EXPECT_THROW(ParseConstraint("beta<f", s.parameters), InputError);
  EXPECT_THROW(ParseConstraint("beta<=m", s.parameters), InputError);
  Residuals residuals(s);
  const Evaluation e = residuals.Evaluate({{1.2, 0.15}}).front();
  EXPECT_EQ(residuals.runs(), 0);
  ASSERT_EQ(e.failures.size(), 1u);
  EXPECT_EQ(e.failures[0], "f=1.2 above beta=0.15 breaks --constraint beta >= f (not run)");
  EXPECT_EQ(e.residuals.size(), 80u);
  Fitter fitter(std::move(s));
  EXPECT_THROW(fitter.Probe(), InputError);
}

}  // namespace fit_test
}  // namespace mechflow::analysis::fit
