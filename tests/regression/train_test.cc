// The train (diagrams/examples/train.xml): a locomotive and N wagons, an
// array of parts/wagon.xml, with friction draft gears between neighbours.
// Whatever the gears do, internal forces cancel: the total momentum is the
// traction force's impulse, and the centre of mass moves as a single body of
// the whole mass M under it. With F(t) = F (1 - exp(-t/tau)):
//   sum m_i v_i = F (t - tau (1 - exp(-t/tau)))
//   sum m_i x_i - sum m_i x_i(0) = F (t^2/2 - tau t + tau^2 (1 - exp(-t/tau)))
// Checked for N = 10 (the example's) and N = 20 (--set N=20), over 3 s.

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/cli/mechflow_command.h"
#include "tests/test_util.h"

namespace mechflow {
namespace {

const std::string kTrain = std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/train.xml";

// The example with every wagon's position and velocity logged as wx<k>, wv<k>
// (sensors of the mechanism on the parts' coordinates w[k].x).
std::string WithWagonSensors(int wagons) {
  std::ifstream in(kTrain);
  std::stringstream text;
  text << in.rdbuf();
  std::string xml = text.str(), sensors, logged;
  for (int k = 0; k < wagons; ++k) {
    const std::string dof = "w[" + std::to_string(k) + "].x", n = std::to_string(k);
    sensors += "<sensor name=\"wx" + n + "\" kind=\"coordinate\" dof=\"" + dof + "\"/>";
    sensors += "<sensor name=\"wv" + n + "\" kind=\"velocity\" dof=\"" + dof + "\"/>";
    logged += "<log signal=\"m.wx" + n + "\" label=\"wx" + n + "\"/><log signal=\"m.wv" + n + "\" label=\"wv" + n + "\"/>";
  }
  xml.insert(xml.find("</mechanism>"), sensors);
  xml.insert(xml.find("</output>"), logged);
  return xml;
}

void ExpectMomentumAndCentreOfMass(int wagons) {
  diagrams::LoadOptions options;
  options.overrides = {{"N", wagons}};
  options.t_end = 3.0;
  // the file's own path: parts/wagon.xml is found beside it
  const testing::XmlRun run =
      testing::RunDescription(diagrams::ReadDiagramText(WithWagonSensors(wagons), kTrain), options);
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const double m_loco = 80000, m_wagon = 20000, F = 200000, tau = 0.5;
  const auto t = run.Column("time"), x_loco = run.Column("x_loco"), v_loco = run.Column("v_loco");
  std::vector<double> momentum(t.size()), moment(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) {
    momentum[i] = m_loco * v_loco[i];
    moment[i] = m_loco * x_loco[i];
  }
  for (int k = 0; k < wagons; ++k) {
    const auto x = run.Column("wx" + std::to_string(k)), v = run.Column("wv" + std::to_string(k));
    EXPECT_DOUBLE_EQ(x[0], -11.0 * (k + 1)) << "wagon " << k;
    for (std::size_t i = 0; i < t.size(); ++i) {
      momentum[i] += m_wagon * v[i];
      moment[i] += m_wagon * x[i];
    }
  }
  const double impulse_end = F * (t.back() - tau * (1 - std::exp(-t.back() / tau)));
  double worst_momentum = 0, worst_moment = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double decay = 1 - std::exp(-t[i] / tau);
    worst_momentum = std::max(worst_momentum, std::abs(momentum[i] - F * (t[i] - tau * decay)));
    worst_moment = std::max(worst_moment, std::abs(moment[i] - moment[0] - F * (t[i] * t[i] / 2 - tau * t[i] + tau * tau * decay)));
  }
  // the gears have moved: the front of the train has pulled away from the rear
  EXPECT_GT(x_loco.back() - x_loco[0], 0.05);
  // at the example's rtol 1e-6, measured 6e-8 (momentum) and 2e-7 .. 5e-7
  // (centre of mass) of the impulse and of impulse times t_end
  std::cout << "N = " << wagons << ": momentum error " << worst_momentum / impulse_end << ", centre of mass error "
            << worst_moment / (impulse_end * t.back()) << " (relative)\n";
  EXPECT_LT(worst_momentum, 1e-6 * impulse_end) << "N = " << wagons;
  EXPECT_LT(worst_moment, 5e-6 * impulse_end * t.back()) << "N = " << wagons;
}

TEST(TrainTest, MomentumIsTheTractionImpulseForTenWagons) { ExpectMomentumAndCentreOfMass(10); }

TEST(TrainTest, MomentumIsTheTractionImpulseForTwentyWagons) { ExpectMomentumAndCentreOfMass(20); }

// The number of wagons is the identifier N: --set N=20 on the command line
// makes wagons w[0] .. w[19], the last 20 lengths behind the locomotive.
TEST(TrainTest, SetNOnTheCommandLineMakesThatManyWagons) {
  const auto check = testing::RunMechflow("check " + kTrain + " --set N=20");
  EXPECT_EQ(check.exit_code, 0) << check.err;
  EXPECT_NE(check.out.find("m.w[19].x0 = -220 m"), std::string::npos) << check.out;
  EXPECT_EQ(check.out.find("m.w[20]."), std::string::npos);
}

}  // namespace
}  // namespace mechflow
