// Long runs (a run must not fail or drift after many cycles): the README's stick-slip example run for
// 5000 s. It used to fail at t = 50.2 s: mid-stick, the regularised friction
// law's near-kinks had polluted CVODE's history until seven error tests in a
// row failed. The simulator now restarts the method from the last accepted
// point (error control unchanged); the limit cycle's period must be the same
// in the last cycles as in the first.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "blocks/solver/simulator.h"
#include "diagrams/loader.h"

namespace mechflow {
namespace {

// Mean period of the maxima of x between t_from and t_to.
double MeanPeriod(const std::vector<double>& t, const std::vector<double>& x, double t_from, double t_to) {
  std::vector<double> peaks;
  for (std::size_t i = 1; i + 1 < x.size(); ++i)
    if (t[i] >= t_from && t[i] <= t_to && x[i] > x[i - 1] && x[i] >= x[i + 1]) peaks.push_back(t[i]);
  EXPECT_GT(peaks.size(), 100u);
  return peaks.size() < 2 ? 0.0 : (peaks.back() - peaks.front()) / (peaks.size() - 1);
}

TEST(LongRunTest, StickSlipGoesOnFor5000SecondsWithAnUnchangedPeriod) {
  diagrams::LoadOptions options;
  options.t_end = 5000;
  diagrams::LoadedDiagram loaded =
      diagrams::LoadDiagram(std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/stick_slip_blocks.xml", options);
  loaded.solver.output_interval = 0.01;  // 500001 rows
  blocks::Simulator sim(*loaded.diagram, loaded.solver, loaded.logged);
  const blocks::RunOutcome outcome = sim.Run();
  ASSERT_TRUE(outcome.ok) << outcome.failure;
  EXPECT_EQ(outcome.t_reached, 5000.0);
  const auto& r = sim.results();
  const auto t = r.Column(0), x = r.Column(r.FindColumn("x"));
  const double first = MeanPeriod(t, x, 0, 100), last = MeanPeriod(t, x, 4900, 5000);
  // about 124 maxima in each window, on a 0.01 s grid: 1e-4 s resolution
  EXPECT_NEAR(last, first, 2e-4);
  EXPECT_NEAR(first, 0.8020, 1e-3);  // README: T = 0.8020 s
  std::printf("period %.5f s over 0..100 s, %.5f s over 4900..5000 s; %ld restarts, %ld steps\n", first, last,
              sim.stats().restarts, sim.stats().steps);
}

}  // namespace
}  // namespace mechflow
