// The mechanism example diagrams (seed models of docs/ELEMENTS.md 9),
// each run and checked against an answer computed independently: closed
// forms, exact kinematics, elliptic integrals, conservation laws.

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "analysis/spectrum.h"
#include "blocks/library/mechanism_block.h"
#include "blocks/solver/simulator.h"
#include "diagrams/loader.h"
#include "tests/numbers.h"

namespace mechflow::mechanism_examples_test {  // names of its own: the files of its folder are compiled together
namespace {

using mechflow::testing::kPi;

struct ExampleRun {
  diagrams::LoadedDiagram loaded;
  std::unique_ptr<blocks::Simulator> sim;
  blocks::RunOutcome outcome;

  explicit ExampleRun(const std::string& example, const diagrams::LoadOptions& options = {})
      : loaded(diagrams::LoadDiagram(std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/" + example, options)) {
    sim = std::make_unique<blocks::Simulator>(*loaded.diagram, loaded.solver, loaded.logged);
    outcome = sim->Run();
  }
  std::vector<double> Column(const std::string& name) const {
    const int c = sim->results().FindColumn(name);
    EXPECT_GE(c, 0) << "no column " << name;
    return c < 0 ? std::vector<double>() : sim->results().Column(c);
  }
  const blocks::MechanismBlock& Mechanism(const std::string& name) const {
    return dynamic_cast<const blocks::MechanismBlock&>(loaded.diagram->block(loaded.diagram->FindBlock(name)));
  }
  // The named mechanism's largest loop-constraint residual in this run.
  double WorstConstraintResidual(const std::string& name) const {
    return Mechanism(name).worst_constraint_residual(sim->context(), loaded.diagram->FindBlock(name));
  }
};

// Times where `x` crosses zero downwards (linear interpolation on the output grid).
std::vector<double> DownCrossings(const std::vector<double>& t, const std::vector<double>& x) {
  std::vector<double> out;
  for (std::size_t i = 1; i < t.size(); ++i)
    if (x[i - 1] > 0 && x[i] <= 0) out.push_back(t[i - 1] + (t[i] - t[i - 1]) * x[i - 1] / (x[i - 1] - x[i]));
  return out;
}
double MeanPeriod(const std::vector<double>& crossings) {
  return (crossings.back() - crossings.front()) / (crossings.size() - 1);
}

// Complete elliptic integral of the first kind by the arithmetic-geometric mean.
double EllipticK(double k) {
  double a = 1, b = std::sqrt(1 - k * k);
  for (int i = 0; i < 30; ++i) {
    const double an = (a + b) / 2;
    b = std::sqrt(a * b);
    a = an;
  }
  return kPi / (2 * a);
}

TEST(MechanismExamplesTest, DampingRatioMatchesClosedFormDR1) {
  ExampleRun run("damping_ratio.xml");
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const double beta = 0.1, w = 2 * kPi, wd = w * std::sqrt(1 - beta * beta);
  const auto t = run.Column("time"), z = run.Column("m.z");
  double worst = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double ref = 0.5 * std::exp(-beta * w * t[i]) *
                       (std::cos(wd * t[i]) + beta / std::sqrt(1 - beta * beta) * std::sin(wd * t[i]));
    worst = std::max(worst, std::abs(z[i] - ref));
  }
  EXPECT_LT(worst, 1e-5);
  // ELEMENTS.md DR-1 table: z(1 s), z(2 s), z(5 s).
  auto at = [&](double time) { return z[static_cast<std::size_t>(std::lround(time / 0.005))]; };
  EXPECT_NEAR(at(1.0), 0.26577, 1e-5);
  EXPECT_NEAR(at(2.0), 0.14112, 1e-5);
  EXPECT_NEAR(at(5.0), 0.02100, 1e-5);
}

TEST(MechanismExamplesTest, ForcesSixSpringsAreOneF1) {
  ExampleRun run("forces.xml");
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto t = run.Column("time");
  const double w = std::sqrt(500.0 / 10.0);
  EXPECT_NEAR(2 * kPi / w, 0.888577, 1e-6);
  std::vector<std::vector<double>> z;
  for (int i = 1; i <= 6; ++i) z.push_back(run.Column("m.z" + std::to_string(i)));
  double spread = 0, closed = 0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    for (int i = 1; i < 6; ++i) spread = std::max(spread, std::abs(z[i][k] - z[0][k]));
    closed = std::max(closed, std::abs(z[0][k] - 0.1 * std::cos(w * t[k])));
  }
  EXPECT_LT(spread, 1e-8);
  EXPECT_LT(closed, 1e-8);
  EXPECT_NEAR(MeanPeriod(DownCrossings(t, z[4])), 0.888577, 1e-5);
}

TEST(MechanismExamplesTest, FrequenciesShowInTheSpectrumOfBody3) {
  // LA-1's frequencies as the three peaks of the power spectral density of
  // z3 that the example asks for (<spectrum>: Welch, 4096-sample Hann
  // segments of 0.5 ms, a bin of 0.49 Hz), each within one bin
  ExampleRun run("frequencies.xml");
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  ASSERT_EQ(run.loaded.spectra.size(), 1u);
  const diagrams::SpectrumRequest& request = run.loaded.spectra[0];
  const auto t = run.Column("time");
  const analysis::Spectrum psd =
      analysis::WelchPsd(run.Column(request.column), t[1] - t[0], {request.segment, request.overlap, analysis::Window::kHann});
  EXPECT_NEAR(psd.resolution, 1.0 / (4096 * 0.0005), 1e-9);
  const auto peaks = analysis::FindPeaks(psd, 3);
  ASSERT_EQ(peaks.size(), 3u);
  std::vector<double> found = {peaks[0].frequency, peaks[1].frequency, peaks[2].frequency};
  std::sort(found.begin(), found.end());
  const double expected[] = {17.6613, 43.8189, 67.2512};
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(found[i], expected[i], psd.resolution) << "spectral peak " << i;
}

TEST(MechanismExamplesTest, PendulumPeriodsSmallAndLargePE1) {
  const double T0 = 2 * kPi * std::sqrt((1.0 / 3.0) / (9.81 * 0.5));  // I_O / (m g l_c)
  {
    ExampleRun run("pendulum.xml");
    ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
    EXPECT_NEAR(MeanPeriod(DownCrossings(run.Column("time"), run.Column("p.phi"))) / T0, 1.0, 1e-4);
  }
  {
    // Large amplitude: T = 4 sqrt(I_O/(m g l_c)) K(sin(phi0/2)).
    diagrams::LoadOptions options;
    options.overrides = {{"phi0", 2.0}};
    ExampleRun run("pendulum.xml", options);
    ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
    const double expected = 4 * std::sqrt((1.0 / 3.0) / (9.81 * 0.5)) * EllipticK(std::sin(1.0));
    EXPECT_NEAR(MeanPeriod(DownCrossings(run.Column("time"), run.Column("p.phi"))) / expected, 1.0, 1e-4);
  }
  {
    ExampleRun run("pendulum_inclined.xml");  // alpha = 60 deg: T = T0 / sqrt(cos alpha)
    ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
    EXPECT_NEAR(MeanPeriod(DownCrossings(run.Column("time"), run.Column("p.phi"))) / T0, std::sqrt(2.0), 1e-4);
  }
}

TEST(MechanismExamplesTest, RoundMovesBody3OnTheCircle) {
  ExampleRun run("round.xml");
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto t = run.Column("time");
  const auto y = run.Column("m.p3[1]"), z = run.Column("m.p3[2]");
  const auto vy = run.Column("m.v3[1]"), vz = run.Column("m.v3[2]");
  const auto ay = run.Column("m.a3[1]"), az = run.Column("m.a3[2]");
  EXPECT_NEAR(y[0], 2.0, 1e-12);
  EXPECT_NEAR(z[0], 0.0, 1e-12);
  for (std::size_t i = 0; i < t.size(); ++i) {
    ASSERT_NEAR(y[i], 2 * std::cos(t[i]), 1e-12);
    ASSERT_NEAR(std::hypot(vy[i], vz[i]), 2.0, 1e-12);
    // 2 m/s^2 toward the centre
    ASSERT_NEAR(ay[i], -y[i], 1e-9);
    ASSERT_NEAR(az[i], -z[i], 1e-9);
  }
}

TEST(MechanismExamplesTest, SliderCrankFollowsExactKinematicsAndStaysClosed) {
  // Table 7.5 read as in the diagram: an offset slider-crank,
  // a cos(theta) + b cos(beta) = -d/4, s = a sin(theta) + b sin(beta) + c - d/2
  ExampleRun run("slider_crank.xml");
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const double a = 0.1, b = 0.3, c = 0.05, d = 0.2;
  const auto theta = run.Column("m.theta"), s = run.Column("m.s"), y = run.Column("m.slider");
  double worst = 0;
  for (std::size_t i = 0; i < theta.size(); ++i) {
    const double cos_beta = -(d / 4 + a * std::cos(theta[i])) / b;
    const double exact = a * std::sin(theta[i]) + b * std::sqrt(1 - cos_beta * cos_beta) + c - d / 2;
    worst = std::max(worst, std::abs(s[i] - exact));
    // the slider's frame (through the tree) lies d/2 beyond the guide coordinate
    // (the loop-closing joint's), up to the loop's residual
    ASSERT_NEAR(y[i], s[i] + d / 2, 1e-9);
  }
  EXPECT_LT(worst, 1e-8);  // measured 1.1e-10 m
  EXPECT_GT(theta.back() - theta.front(), 4 * kPi) << "the crank should turn round";
  EXPECT_LT(run.WorstConstraintResidual("m"), 1e-8);
}

// Convel2 with the bushing removed (the seed's Fig. 7.17 run, 500 s):
// nothing holds the second shaft's inclination any more, and the speeds part.
TEST(MechanismExamplesTest, Convel2LosesItsInclinationWithoutTheBushing) {
  diagrams::LoadOptions held_options, removed_options;
  held_options.variants = {"Bushing held"};
  removed_options.variants = {"Bushing removed"};
  ExampleRun held("convel2.xml", held_options), removed("convel2.xml", removed_options);
  ASSERT_TRUE(held.outcome.ok) << held.outcome.failure;
  ASSERT_TRUE(removed.outcome.ok) << removed.outcome.failure;
  EXPECT_EQ(removed.loaded.solver.t_end, 500.0);
  auto tilt_range = [](const std::vector<double>& tilt) {
    return *std::max_element(tilt.begin(), tilt.end()) - *std::min_element(tilt.begin(), tilt.end());
  };
  auto speed_spread = [](const ExampleRun& run) {
    const auto w1 = run.Column("cv.w1"), w2 = run.Column("cv.w2");
    double spread = 0;
    for (std::size_t i = 0; i < w1.size(); ++i) spread = std::max(spread, std::abs(w1[i] - w2[i]));
    return spread;
  };
  const auto held_tilt = held.Column("shaft 2 tilt"), removed_tilt = removed.Column("shaft 2 tilt");
  EXPECT_NEAR(held_tilt.front(), 10.0, 1e-9);  // alpha
  EXPECT_NEAR(removed_tilt.front(), 10.0, 1e-9);
  EXPECT_LT(tilt_range(held_tilt), 1e-3);      // held at alpha
  EXPECT_GT(tilt_range(removed_tilt), 5.0);    // measured: to 0.0004 deg at 328 s and back to 7.6
  EXPECT_GT(speed_spread(removed), 10 * speed_spread(held));
}

TEST(MechanismExamplesTest, FourBarStaysClosedOverTenSeconds) {
  ExampleRun run("four_bar.xml");
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  EXPECT_LT(run.WorstConstraintResidual("m"), 1e-8);
  EXPECT_GT(run.WorstConstraintResidual("m"), 0.0);
}

TEST(MechanismExamplesTest, Convel1ShaftsTurnTogetherCV1AndConvel2NearlySo) {
  const double expected = 0.01 / (0.1 * 0.2) * (1 - std::exp(-1.0));  // 0.316060
  ExampleRun one("convel1.xml");
  ASSERT_TRUE(one.outcome.ok) << one.outcome.failure;
  const auto w1 = one.Column("cv.w1"), w2 = one.Column("cv.w2");
  for (std::size_t i = 0; i < w1.size(); ++i) ASSERT_NEAR(w1[i], w2[i], 1e-9);
  EXPECT_NEAR(w1.back(), expected, 1e-7);
  ExampleRun two("convel2.xml");
  ASSERT_TRUE(two.outcome.ok) << two.outcome.failure;
  const auto u1 = two.Column("cv.w1"), u2 = two.Column("cv.w2");
  double spread = 0;
  for (std::size_t i = 0; i < u1.size(); ++i) spread = std::max(spread, std::abs(u1[i] - u2[i]));
  EXPECT_GT(spread, 0.0);
  EXPECT_LT(spread, 1e-3 * expected);
  EXPECT_NEAR(u1.back(), expected, 1e-3 * expected);
}

TEST(MechanismExamplesTest, MathGamePursuerNeverCatchesTheTarget) {
  ExampleRun run("math_game.xml");
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto t = run.Column("time"), d = run.Column("g.distance");
  const auto ax = run.Column("g.acceleration[0]"), ay = run.Column("g.acceleration[1]"),
             az = run.Column("g.acceleration[2]");
  for (std::size_t i = 0; i < t.size(); ++i)
    ASSERT_NEAR(std::sqrt(ax[i] * ax[i] + ay[i] * ay[i] + az[i] * az[i]), 50.0 / 3.0, 1e-9);
  const auto closest = std::min_element(d.begin(), d.end());
  EXPECT_GT(*closest, 0.05 + 0.05);
  // ELEMENTS.md 9.13: 0.402 m at about 11.7 s (on the 0.01 s output grid).
  EXPECT_NEAR(*closest, 0.402, 1e-3);
  EXPECT_NEAR(t[closest - d.begin()], 11.7, 0.05);
  // the logged paths: the target on its circle, the distance between the two
  const auto ty = run.Column("g.target_y"), tz = run.Column("g.target_z"), py = run.Column("g.pursuer_y"),
             pz = run.Column("g.pursuer_z");
  for (std::size_t i = 0; i < t.size(); ++i) {
    ASSERT_NEAR(ty[i], 2 * std::cos(t[i]), 1e-12);
    ASSERT_NEAR(tz[i], 2 * std::sin(t[i]), 1e-12);
    ASSERT_NEAR(std::hypot(ty[i] - py[i], tz[i] - pz[i]), d[i], 1e-12);
  }
}

TEST(MechanismExamplesTest, PendulumChainConservesEnergy) {
  ExampleRun run("pendulum_chain.xml");
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto t = run.Column("time");
  std::vector<double> energy(t.size(), 0.0), kinetic(t.size(), 0.0);
  for (int i = 1; i <= 5; ++i) {
    const std::string n = std::to_string(i);
    const auto z = run.Column("chain.p" + n + "[2]");
    const auto vx = run.Column("chain.v" + n + "[0]"), vy = run.Column("chain.v" + n + "[1]"),
               vz = run.Column("chain.v" + n + "[2]"), wx = run.Column("chain.w" + n + "[0]");
    for (std::size_t k = 0; k < t.size(); ++k) {
      const double ke = 0.5 * (vx[k] * vx[k] + vy[k] * vy[k] + vz[k] * vz[k]) + 0.5 / 12.0 * wx[k] * wx[k];
      kinetic[k] += ke;
      energy[k] += ke + 9.81 * z[k];
    }
  }
  // Relative to the largest kinetic energy reached (the energy itself starts at 0).
  const double scale = *std::max_element(kinetic.begin(), kinetic.end());
  double drift = 0;
  for (double e : energy) drift = std::max(drift, std::abs(e - energy[0]));
  EXPECT_LT(drift / scale, 1e-6) << "scale " << scale;
}

}  // namespace
}  // namespace mechflow::mechanism_examples_test
