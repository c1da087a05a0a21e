// The stick-slip oscillator's static and dynamic friction coefficients from
// its measured position: synthetic measurements made by the model with known
// coefficients plus seeded noise, recovered within two standard errors; the
// standard errors agree with the spread of the estimates over 100 noise
// seeds (a Monte Carlo of the noise) within 30 %.
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "analysis/fit/fit.h"
#include "diagrams/xml_reader.h"
#include "run/model.h"
#include "run/sinks.h"

namespace mechflow::analysis::fit {
namespace fit_stick_slip_test {

const std::string kStickSlip = std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/stick_slip_blocks.xml";
constexpr double kSigma = 2e-4;  // m, the position's noise

// x of the oscillator with mu_s = 0.6, mu_d = 0.4 every 20 ms for 2.5 s
// (three stick-slip cycles): the model's own, as a perfect instrument.
std::vector<double> TrueTimes() {
  std::vector<double> t;
  for (int i = 1; i <= 125; ++i) t.push_back(0.02 * i);
  return t;
}

std::vector<double> TruePositions() {
  run::Model model(kStickSlip);
  run::RunOptions options;
  options.times = TrueTimes();
  options.log = std::vector<std::string>{"x.y"};
  run::MemorySink rows;
  EXPECT_EQ(model.Run(options, &rows).status, run::Status::kOk);
  return rows.columns()[1];
}

// From mu_s = 0.5, mu_d = 0.3, or (`near`) from the truth: the Monte Carlo's
// fits after the first need not walk the whole way again.
fit::Setup StickSlip(const std::vector<double>& truth, unsigned seed, bool near = false) {
  std::mt19937 random(seed);
  std::normal_distribution<double> noise(0.0, kSigma);
  Experiment e;
  e.file = "position.csv";
  e.times = TrueTimes();
  e.measured = {truth};
  for (double& x : e.measured[0]) x += noise(random);
  for (std::size_t i = 0; i < e.times.size(); ++i) e.lines.push_back(static_cast<int>(i) + 2);
  fit::Setup s;
  s.diagram = kStickSlip;
  s.description = diagrams::ReadDiagramFile(kStickSlip);
  s.common.overrides = {{"mu_s", near ? 0.6 : 0.5}, {"mu_d", near ? 0.4 : 0.3}};  // the start
  fit::Match match;
  match.signal = "x.y";
  match.column = "x";
  match.weight = 1.0 / kSigma;
  s.matches = {match};
  s.experiments = {std::move(e)};
  s.parameters = {ParseFree("mu_s=0.3:1"), ParseFree("mu_d=0.1:0.55")};
  s.threads = 2;
  return s;
}

TEST(FitStickSlip, RecoversFrictionWithinItsStandardErrors) {
  const std::vector<double> truth = TruePositions();
  const double mu[] = {0.6, 0.4};
  std::vector<std::vector<double>> estimates(2);
  std::vector<double> reported;
  for (unsigned seed = 1; seed <= 100; ++seed) {
    Fitter fitter(StickSlip(truth, seed, seed > 1));
    if (seed == 1) fitter.Probe();
    const FitResult r = fitter.Run({});
    ASSERT_TRUE(r.optimiser.converged) << "seed " << seed << ": " << r.optimiser.report;
    ASSERT_TRUE(r.failures.empty());
    if (seed == 1) {
      reported = r.statistics.standard_error;
      for (int j = 0; j < 2; ++j) EXPECT_NEAR(r.values[j], mu[j], 2 * reported[j]) << "parameter " << j;
    }
    for (int j = 0; j < 2; ++j) estimates[j].push_back(r.values[j]);
  }
  for (int j = 0; j < 2; ++j) {
    double mean = 0, square = 0;
    for (const double v : estimates[j]) mean += v / 100;
    for (const double v : estimates[j]) square += (v - mean) * (v - mean) / 99;
    EXPECT_NEAR(mean, mu[j], 3 * reported[j] / 10);  // unbiased: within 3 standard errors of the mean of 100
    EXPECT_NEAR(std::sqrt(square), reported[j], 0.3 * reported[j]) << "parameter " << j;
    std::printf("parameter %d: standard error %.3g, Monte Carlo %.3g, mean %.6f\n", j, reported[j], std::sqrt(square),
                mean);
  }
}

}  // namespace fit_stick_slip_test
}  // namespace mechflow::analysis::fit
