// Energy: in every seed model without external work,
// dampers or friction, the mechanism's kinetic plus gravitational potential
// energy, as its sensors report it, stays constant to the solver's accuracy.
#include <algorithm>
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "tests/test_util.h"

namespace mechflow {
namespace {

std::string WithEnergySensors(const std::string& example) {
  std::string xml = testing::ReadExample(example);
  const auto name_at = xml.find("\"", xml.find("name=", xml.find("<mechanism"))) + 1;
  const std::string mechanism = xml.substr(name_at, xml.find('"', name_at) - name_at);
  const auto mechanism_end = xml.find("</mechanism>");
  const auto output_end = xml.find("</output>");
  EXPECT_NE(mechanism_end, std::string::npos);
  EXPECT_NE(output_end, std::string::npos);
  xml.insert(output_end, "<log signal=\"" + mechanism + ".T\" label=\"T\"/><log signal=\"" + mechanism +
                             ".V\" label=\"V\"/>");
  xml.insert(mechanism_end,
             "<sensor name=\"T\" kind=\"kinetic_energy\"/><sensor name=\"V\" kind=\"potential_energy\"/>");
  return xml;
}

class ConservativeExample : public ::testing::TestWithParam<const char*> {};

TEST_P(ConservativeExample, KineticPlusPotentialEnergyStaysConstant) {
  const testing::XmlRun run = testing::RunXml(WithEnergySensors(GetParam()));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto T = run.Column("T"), V = run.Column("V");
  const double largest = *std::max_element(T.begin(), T.end());
  ASSERT_GT(largest, 1e-6) << "the example should move";
  double drift = 0.0;
  for (std::size_t i = 0; i < T.size(); ++i) drift = std::max(drift, std::abs(T[i] + V[i] - T[0] - V[0]));
  // rtol 1e-8 or 1e-9 in these examples; measured drifts 2.0e-7 .. 5.6e-7 of the largest kinetic
  // energy, 3.1e-6 for four_bar_train
  EXPECT_LT(drift, 1e-5 * largest) << GetParam();
  RecordProperty("relative_drift", std::to_string(drift / largest));
  std::cout << GetParam() << ": energy drift " << drift / largest << " of the largest kinetic energy\n";
}

INSTANTIATE_TEST_SUITE_P(Examples, ConservativeExample,
                         ::testing::Values("pendulum.xml", "pendulum_inclined.xml", "pendulum_chain.xml",
                                           "four_bar.xml", "four_bar_train.xml", "bricard.xml",
                                           "coupling_rods.xml", "slider_crank.xml", "bricard_iftomm.xml"));

}  // namespace
}  // namespace mechflow
