// Welch power spectral density (analysis/spectrum.h) against what a PSD
// must satisfy: Parseval (its integral is the signal's variance), the level
// of white noise, peaks where the sines are.
#include <cmath>
#include <csignal>
#include <random>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "analysis/spectrum.h"
#include "tests/numbers.h"
#include "tests/test_util.h"

namespace mechflow::analysis {
namespace {

using mechflow::testing::kPi;

std::vector<double> Sines(int n, double dt, std::vector<std::pair<double, double>> amplitude_frequency) {
  std::vector<double> x(n, 0.3);  // an offset, which the mean removal takes out
  for (int k = 0; k < n; ++k)
    for (const auto& [a, f] : amplitude_frequency) x[k] += a * std::sin(2 * kPi * f * k * dt + 0.4);
  return x;
}

double Integral(const Spectrum& s) {
  double sum = 0.0;
  for (double p : s.density) sum += p * s.resolution;
  return sum;
}

TEST(SpectrumTest, ASineIntegratesToItsVarianceParseval) {
  // 2.5 sin at 13.7 Hz (between bins), 1 kHz for 20 s: variance 2.5^2 / 2
  const std::vector<double> x = Sines(20000, 1e-3, {{2.5, 13.7}});
  for (const Window w : {Window::kHann, Window::kRectangular}) {
    const Spectrum s = WelchPsd(x, 1e-3, {2048, 0.5, w});
    EXPECT_NEAR(Integral(s), 2.5 * 2.5 / 2, 0.01 * 2.5 * 2.5 / 2);
    EXPECT_EQ(s.segment, 2048);
    EXPECT_EQ(s.segments, 18);  // (20000 - 2048) / 1024 + 1
    EXPECT_NEAR(s.frequency.back(), 500.0, 1e-9);
  }
}

TEST(SpectrumTest, WhiteNoiseIsFlatAtItsLevel) {
  // variance 4 at fs = 200 Hz: one-sided density 2 * 4 / 200 = 0.04 per Hz
  std::mt19937 random(7);
  std::normal_distribution<double> noise(0.0, 2.0);
  std::vector<double> x(400000);
  for (double& v : x) v = noise(random);
  const Spectrum s = WelchPsd(x, 1.0 / 200, {512, 0.5, Window::kHann});
  double mean = 0.0;
  for (std::size_t k = 1; k + 1 < s.density.size(); ++k) mean += s.density[k];
  mean /= s.density.size() - 2;
  EXPECT_NEAR(mean, 0.04, 0.02 * 0.04);
  // flat: every bin within 25 % of that (1561 segments average it)
  for (std::size_t k = 1; k + 1 < s.density.size(); ++k) EXPECT_NEAR(s.density[k], 0.04, 0.25 * 0.04) << k;
  EXPECT_NEAR(Integral(s), 4.0, 0.02 * 4.0);
}

TEST(SpectrumTest, PeaksWhereTheSinesAre) {
  const std::vector<double> x = Sines(1 << 16, 1e-3, {{1.0, 17.66}, {0.3, 43.82}, {0.1, 67.25}});
  const Spectrum s = WelchPsd(x, 1e-3, {4096, 0.5, Window::kHann});
  const std::vector<SpectralPeak> peaks = FindPeaks(s, 3);
  ASSERT_EQ(peaks.size(), 3u);
  EXPECT_NEAR(peaks[0].frequency, 17.66, s.resolution);
  EXPECT_NEAR(peaks[1].frequency, 43.82, s.resolution);
  EXPECT_NEAR(peaks[2].frequency, 67.25, s.resolution);
  EXPECT_GT(peaks[0].level, peaks[1].level);
}

TEST(SpectrumTest, RefusesWhatItCannotEstimate) {
  EXPECT_THAT(testing::InputErrorOf([] { WelchPsd(std::vector<double>(100, 1.0), 0.01, {256, 0.5, Window::kHann}); }),
              ::testing::HasSubstr("fewer than one segment of 256"));
  EXPECT_THAT(testing::InputErrorOf([] { WelchPsd(std::vector<double>(1000, 1.0), 0.01, {256, 1.0, Window::kHann}); }),
              ::testing::HasSubstr("overlap"));
  EXPECT_THAT(testing::InputErrorOf([] { ParseWindow("hamming", "test"); }), ::testing::HasSubstr("hann or rectangular"));
}

// The transforms may cover the signal at most kMaxCoverage times over: an
// overlap near 1 would otherwise transform nearly every sample offset (on a
// million rows, 737,856 transforms of 2^18 points).
TEST(SpectrumTest, TheWorkIsBoundedByTheSignalsLength) {
  const std::vector<double> x = Sines(20000, 1e-3, {{1.0, 13.7}});
  // 0.9999999 steps one sample at a time: 17,953 segments of 2048
  EXPECT_THAT(testing::InputErrorOf([&] { WelchPsd(x, 1e-3, {2048, 0.9999999, Window::kHann}); }),
              ::testing::HasSubstr("overlap 0.9999999 is not from 0 to 0.99"));
  // at 0.99 a segment of 149 still steps one sample (1.49 rounds to 1): 149 times over
  EXPECT_THAT(testing::InputErrorOf([&] { WelchPsd(x, 1e-3, {149, 0.99, Window::kHann}); }),
              ::testing::HasSubstr("more than 100 times over; lower the overlap"));
  // within the bound: (20000 - 1024) / 10 + 1 segments of 1024, 97 times over
  const Spectrum s = WelchPsd(x, 1e-3, {1024, 0.99, Window::kHann});
  EXPECT_EQ(s.segments, 1898);
  EXPECT_LE(double(s.segments) * s.segment, kMaxCoverage * 20000.0);
}

TEST(SpectrumTest, AnInterruptStopsTheTransforms) {
  const std::vector<double> x = Sines(4096, 1e-3, {{1.0, 13.7}});
  volatile std::sig_atomic_t flag = SIGTERM;  // as the command's handler sets it
  WelchOptions options{256, 0.5, Window::kHann, &flag};
  try {
    WelchPsd(x, 1e-3, options);
    ADD_FAILURE() << "not interrupted";
  } catch (const Interrupted& e) {
    EXPECT_EQ(e.signal(), SIGTERM);
    EXPECT_STREQ(e.what(), "interrupted by SIGTERM");
  }
  flag = 0;  // no signal: the whole estimate
  EXPECT_EQ(WelchPsd(x, 1e-3, options).segments, 31);
}

TEST(SpectrumTest, ANegativePeakCountIsBadInputNotACrash) {
  const Spectrum s = WelchPsd(Sines(4096, 1e-3, {{1.0, 13.7}}), 1e-3, {256, 0.5, Window::kHann});
  EXPECT_THAT(testing::InputErrorOf([&] { FindPeaks(s, -1); }), ::testing::HasSubstr("peaks must be 0 or more"));
  EXPECT_TRUE(FindPeaks(s, 0).empty());
}

}  // namespace
}  // namespace mechflow::analysis
