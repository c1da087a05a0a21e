// The parallelogram ladder written as an array of parts
// (diagrams/examples/parallelogram_ladder.xml, N rungs of
// parts/parallelogram.xml) against the closed form of the coupled cranks
// (the same as tests/regression/singular_position_test.cc's for the ladder
// written out in full): every crank keeps the angle theta of the first, and
//   I theta'^2 / 2 + V(theta) is constant,
//   I = (N + 1) m_c a^2 / 3 + N m_r a^2,   V = g ((N + 1) m_c a / 2 + N m_r a) sin(theta).

#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/numbers.h"
#include "tests/test_util.h"

namespace mechflow {
namespace {

using mechflow::testing::kPi;
const std::string kLadder = std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/parallelogram_ladder.xml";

// The example with the last crank's angle logged as "last" (its pivot
// r[N-1].pivot, a coordinate of the array's last part).
std::string WithLastCrank(int rods) {
  std::ifstream in(kLadder);
  std::stringstream text;
  text << in.rdbuf();
  std::string xml = text.str();
  xml.insert(xml.find("</mechanism>"),
             "<sensor name=\"last\" kind=\"coordinate\" dof=\"r[" + std::to_string(rods - 1) + "].pivot\"/>");
  xml.insert(xml.find("</output>"), "<log signal=\"m.last\" label=\"last\"/>");
  return xml;
}

TEST(ParallelogramLadderTest, ArrayOfFourBarsKeepsTheEnergyOfTheCoupledCranks) {
  const int rods = 3;
  diagrams::LoadOptions options;
  options.overrides = {{"N", rods}};
  options.t_end = 2.0;  // over the top twice: four common dead centres
  const testing::XmlRun run = testing::RunDescription(diagrams::ReadDiagramText(WithLastCrank(rods), kLadder), options);
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const double g = 9.81, a = 0.5, m_c = 0.5, m_r = 1.0;
  const double inertia = (rods + 1) * m_c * a * a / 3 + rods * m_r * a * a;
  const double weight = g * ((rods + 1) * m_c * a / 2 + rods * m_r * a);
  const auto theta = run.Column("crank"), rate = run.Column("speed"), last = run.Column("last");
  const double e0 = inertia * rate[0] * rate[0] / 2 + weight * std::sin(theta[0]);
  double drift = 0, spread = 0;
  for (std::size_t i = 0; i < theta.size(); ++i) {
    drift = std::max(drift, std::abs(inertia * rate[i] * rate[i] / 2 + weight * std::sin(theta[i]) - e0) / e0);
    spread = std::max(spread, std::abs(last[i] - theta[i]));
  }
  std::cout << "N = " << rods << ": energy drift " << drift << ", crank spread " << spread << "\n";
  EXPECT_GT(theta.back() - theta.front(), 4 * kPi);
  // at the example's rtol 1e-9, measured 9.3e-8 and 5e-13; the bounds are
  // singular_position_test's for the ladder written out in full
  EXPECT_LT(drift, 2000 * 1e-9);
  EXPECT_LT(spread, 1e-9);
}

TEST(ParallelogramLadderTest, FortyRungsLoad) {
  const diagrams::LoadedDiagram loaded = diagrams::LoadDiagram(kLadder);
  int rungs = 0;
  for (const auto& instance : loaded.description.instances) rungs += instance.path.rfind("m.r[", 0) == 0;
  EXPECT_EQ(rungs, 40);
}

}  // namespace
}  // namespace mechflow
