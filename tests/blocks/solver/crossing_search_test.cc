// CrossingSearch (blocks/solver/crossing_search.h): CVODE's rules for where a
// zero-crossing function counts as crossed, and the located instant, on
// functions whose roots are known in closed form.
#include "blocks/solver/crossing_search.h"

#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

namespace mechflow::blocks {
namespace {

using Functions = std::function<std::vector<double>(double)>;

// Checks the functions at `times` in order, as the simulator does, and
// locates the first crossing; returns its time, or NaN when none.
double FirstCrossing(CrossingSearch* search, const Functions& g, const std::vector<double>& times, double ttol) {
  search->Start(times.front(), g(times.front()));
  for (std::size_t k = 1; k < times.size(); ++k) {
    const std::vector<double> values = g(times[k]);
    if (!search->Crosses(values)) {
      search->Accept(times[k], values);
      continue;
    }
    return search->Locate(times[k], values, ttol, [&](double t, std::span<double> out) {
      const std::vector<double> v = g(t);
      std::copy(v.begin(), v.end(), out.begin());
    });
  }
  return std::numeric_limits<double>::quiet_NaN();
}

constexpr double kTol = 1e-12;

TEST(CrossingSearchTest, LocatesARisingCrossingPastTheRootWithinTheTolerance) {
  CrossingSearch search({+1});
  const double t = FirstCrossing(&search, [](double t) { return std::vector<double>{t - 0.3}; }, {0.0, 0.25, 0.5}, kTol);
  EXPECT_GE(t, 0.3);  // the state there is across the crossing
  EXPECT_LE(t, 0.3 + kTol);
  EXPECT_EQ(search.directions_found(), std::vector<int>{+1});
}

TEST(CrossingSearchTest, IllinoisConvergesOnACurvedFunctionInFewEvaluations) {
  CrossingSearch search({0});
  // cos t - 1/2 falls through zero at pi/3; the secant alone would creep from one side
  const double t = FirstCrossing(&search, [](double t) { return std::vector<double>{std::cos(t) - 0.5}; }, {0.0, 2.0},
                                 kTol);
  EXPECT_NEAR(t, std::numbers::pi / 3, kTol);
  EXPECT_EQ(search.directions_found(), std::vector<int>{-1});
  EXPECT_LE(search.evaluations(), 20);  // bisection would take 41
}

TEST(CrossingSearchTest, ACrossingAgainstTheAllowedDirectionDoesNotCount) {
  CrossingSearch search({-1});  // falling only
  const double t = FirstCrossing(&search, [](double t) { return std::vector<double>{t - 0.3}; }, {0.0, 0.5, 1.0}, kTol);
  EXPECT_TRUE(std::isnan(t));
}

TEST(CrossingSearchTest, TheEarliestOfSeveralCrossingsInOneIntervalLeads) {
  CrossingSearch search({0, 0, 0});
  const Functions g = [](double t) { return std::vector<double>{t - 0.4, 0.35 - t, 2.0}; };
  const double t = FirstCrossing(&search, g, {0.0, 1.0}, kTol);
  EXPECT_NEAR(t, 0.35, kTol);
  EXPECT_EQ(search.directions_found(), (std::vector<int>{0, -1, 0}));
}

TEST(CrossingSearchTest, ChecksBetweenStepEndsSeeACrossingThatReturns) {
  // up through zero at 0.2 and back at 0.6: invisible from 0 and 1 alone
  const Functions g = [](double t) { return std::vector<double>{(t - 0.2) * (0.6 - t)}; };
  CrossingSearch search({0});
  EXPECT_TRUE(std::isnan(FirstCrossing(&search, g, {0.0, 1.0}, kTol)));
  const double t = FirstCrossing(&search, g, {0.0, 0.5, 1.0}, kTol);
  EXPECT_NEAR(t, 0.2, kTol);
  EXPECT_EQ(search.directions_found(), std::vector<int>{+1});
}

TEST(CrossingSearchTest, AFunctionZeroAtTheStartWaitsUntilItIsSeenNonzero) {
  // -t starts exactly at zero (a contact closed at the start) and falls:
  // no crossing; once nonzero it counts as any other
  CrossingSearch search({0});
  const Functions g = [](double t) { return std::vector<double>{t < 0.5 ? -t : t - 0.75}; };
  search.Start(0.0, g(0.0));
  EXPECT_TRUE(search.AnyInactive());
  EXPECT_FALSE(search.Crosses(g(0.25)));
  search.Accept(0.25, g(0.25));
  EXPECT_FALSE(search.AnyInactive());
  EXPECT_TRUE(search.Crosses(g(1.0)));
}

TEST(CrossingSearchTest, TheProbeActivatesAFunctionThatLeftZero) {
  CrossingSearch search({+1});
  search.Start(0.0, std::vector<double>{0.0});
  search.Probe(std::vector<double>{-1e-3});  // just after the start: below zero
  EXPECT_FALSE(search.AnyInactive());
  EXPECT_TRUE(search.Crosses(std::vector<double>{0.5}));  // and rises through it
}

TEST(CrossingSearchTest, AnExactZeroAtTheCheckIsTheCrossingWithoutEvaluating) {
  CrossingSearch search({0});
  search.Start(0.0, std::vector<double>{-1.0});
  ASSERT_TRUE(search.Crosses(std::vector<double>{0.0}));
  const double t = search.Locate(0.5, std::vector<double>{0.0}, kTol,
                                 [](double, std::span<double>) { FAIL() << "no evaluation needed"; });
  EXPECT_EQ(t, 0.5);
  EXPECT_EQ(search.directions_found(), std::vector<int>{+1});
}

}  // namespace
}  // namespace mechflow::blocks
