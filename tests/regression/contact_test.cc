// Points-plane contact (ELEMENTS.md 5.1, test CT-1): a unit mass dropped at
// 1 m/s on a linear spring-damper contact rebounds with the restitution of
// the clipped law (the force never pulls), computed independently in the
// ELEMENTS.md table.

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "tests/test_util.h"

namespace mechflow {
namespace {

std::string Drop(double beta) {
  return "<diagram>\n<identifiers><identifier name=\"beta\" value=\"" + std::to_string(beta) +
         "\"/></identifiers>\n"
         "<mechanism name=\"m\" gravity=\"0 0 0\">\n"
         "<body name=\"Ball\" mass=\"1\" inertia=\"0.1 0.1 0.1\"/>\n"
         "<joint name=\"z\" type=\"translational\" body1=\"Base0\" body2=\"Ball\" axis=\"0 0 1\" q0=\"0.01\" v0=\"-1\"/>\n"
         "<contact name=\"floor\" type=\"points_plane\" body1=\"Ball\" points=\"0 0 0\" body2=\"Base0\" normal=\"0 0 1\"\n"
         "         stiffness=\"1e4\" damping=\"2*beta*sqrt(1e4)\"/>\n"
         "<sensor name=\"v\" kind=\"velocity\" dof=\"z\"/>\n"
         "<sensor name=\"n\" kind=\"element\" element=\"floor\" quantity=\"normal\"/>\n"
         "</mechanism>\n<solver t_end=\"0.1\" rtol=\"1e-9\" atol=\"1e-12\"/>\n"
         "<output interval=\"0.0001\"><log signal=\"m.v\"/><log signal=\"m.n\"/></output>\n</diagram>\n";
}

TEST(ContactTest, ReboundOfTheClippedLinearLawCT1) {
  const double beta[4] = {0.05, 0.1, 0.2, 0.3};
  const double restitution[4] = {0.8588, 0.7441, 0.5717, 0.4510};  // ELEMENTS.md 5.1, clipped
  for (int k = 0; k < 4; ++k) {
    const auto run = testing::RunXml(Drop(beta[k]));
    ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
    const auto v = run.Column("m.v"), n = run.Column("m.n");
    EXPECT_NEAR(v.back(), restitution[k], 5e-4) << "beta " << beta[k];
    EXPECT_GE(*std::min_element(n.begin(), n.end()), 0.0) << "the contact must never pull";
    // touching and leaving are events
    EXPECT_EQ(run.sim->events().size(), 2u);
  }
}

}  // namespace
}  // namespace mechflow
