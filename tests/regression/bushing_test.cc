// Bushing BU-1 (ELEMENTS.md 4): a 10 kg body held by a bushing with only
// c_z = 39 478.4 N/m hangs at the sag m g / c_z = 2.485 mm and oscillates
// vertically at 10.000 Hz -- found here by the linear analysis at the static
// equilibrium and by a run started at rest from the unloaded position.

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "analysis/linearization.h"
#include "tests/test_util.h"

namespace mechflow {
namespace {

const char* kBushing =
    "<diagram>\n<mechanism name=\"m\">\n"
    "<body name=\"B\" mass=\"10\" inertia=\"0.1 0.1 0.1\"/>\n"
    "<joint name=\"free\" type=\"quaternion\" body1=\"Base0\" body2=\"B\"/>\n"
    "<bushing name=\"bush\" body1=\"Base0\" body2=\"B\" c=\"0 0 39478.4\" ca=\"100 100 100\"/>\n"
    "<sensor name=\"z\" kind=\"position\" body=\"B\" component=\"z\"/>\n"
    "</mechanism>\n<solver t_end=\"1\" rtol=\"1e-10\" atol=\"1e-12\"/>\n"
    "<output interval=\"0.0005\"><log signal=\"m.z\"/></output>\n</diagram>\n";

TEST(BushingTest, SagAndFrequencyBU1) {
  // x and y are free (no stiffness): lateral motions are rigid-body modes.
  const auto loaded = testing::LoadXml(kBushing);
  blocks::Context ctx;
  std::vector<double> x;
  analysis::PrepareContext(*loaded.diagram, 0.0, &ctx, &x);
  analysis::FindEquilibrium(*loaded.diagram, &ctx, &x);
  const double sag = 10 * 9.81 / 39478.4;
  EXPECT_NEAR(sag, 2.485e-3, 1e-6);
  EXPECT_NEAR(x[2], -sag, 1e-9);  // the joint's z coordinate
  const auto modes = analysis::ModalAnalysis(analysis::StateJacobian(*loaded.diagram, &ctx, x));
  const auto vertical = std::find_if(modes.begin(), modes.end(), [](const analysis::Mode& m) {
    return std::abs(m.frequency_hz - 10.0) < 0.5;
  });
  ASSERT_NE(vertical, modes.end());
  EXPECT_NEAR(vertical->frequency_hz, 10.000, 1e-3);

  // Released at rest unloaded: z swings between 0 and -2 sag at 10 Hz.
  const auto run = testing::RunXml(kBushing);
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto z = run.Column("m.z");
  EXPECT_NEAR(*std::min_element(z.begin(), z.end()), -2 * sag, 1e-6);
  EXPECT_NEAR(z[100], -2 * sag, 1e-6);  // half a period: 0.05 s
}

}  // namespace
}  // namespace mechflow
