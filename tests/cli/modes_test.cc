// `mechflow modes`: natural frequencies of the seed models (ELEMENTS.md 8, LA-1, DR-1).
#include <cmath>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "analysis/linearization.h"
#include "cli/commands.h"

namespace mechflow::cli::modes_test {  // names of its own: the files of its folder are compiled together
namespace {

std::string Example(const std::string& name) {
  return std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/" + name;
}

// Rows of NAME.modes.csv after running `mechflow modes` on an example
// (each example's diagram is named after its file).
std::vector<std::vector<double>> Modes(const std::string& example, std::vector<std::string> extra = {}) {
  const std::string dir = ::testing::TempDir() + "/modes_" + example;
  std::vector<std::string> argv = {"modes", Example(example), "--out", dir};
  argv.insert(argv.end(), extra.begin(), extra.end());
  std::ostringstream out, err;
  EXPECT_EQ(Main(argv, out, err), 0) << err.str();
  const std::string name = example.substr(0, example.find('.'));
  std::ifstream csv(dir + "/" + name + ".modes.csv");
  EXPECT_TRUE(csv) << "no " << name << ".modes.csv in " << dir;
  std::string line;
  std::getline(csv, line);  // header
  std::vector<std::vector<double>> rows;
  while (std::getline(csv, line)) {
    std::vector<double> row;
    std::stringstream fields(line);
    for (std::string f; std::getline(fields, f, ',');) row.push_back(std::stod(f));
    rows.push_back(row);
  }
  return rows;
}

TEST(ModesTest, FrequenciesGivesTheSeedsThreeFrequenciesLA1) {
  const auto rows = Modes("frequencies.xml");
  ASSERT_EQ(rows.size(), 3u);
  const double expected[3] = {17.6613, 43.8189, 67.2512};
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(rows[k][1], expected[k], 1e-4);
    EXPECT_NEAR(rows[k][3], 0.0, 1e-9);
  }
}

TEST(ModesTest, DampingRatioGivesDampedFrequencyAndRatioDR1) {
  const auto rows = Modes("damping_ratio.xml");
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_NEAR(rows[0][1], 0.994987, 1e-6);
  EXPECT_NEAR(rows[0][2], 1.0, 1e-6);
  EXPECT_NEAR(rows[0][3], 0.1, 1e-6);
}

TEST(ModesTest, EquilibriumOfAHangingPendulumStartedAside) {
  // Started at 0.5 rad, the equilibrium is found at 0 and the small-amplitude
  // frequency sqrt(m g l_c / I_O) / 2 pi follows.
  const auto rows = Modes("pendulum.xml", {"--set", "phi0=0.5", "--equilibrium"});
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_NEAR(rows[0][1], std::sqrt(9.81 * 0.5 / (1.0 / 3.0)) / (2 * M_PI), 1e-6);
}

TEST(ModesTest, JacobianOfALinearSystemIsExact) {
  // A = [[0, 1], [-4, -0.4]]: eigenvalues -0.2 +- i sqrt(3.96).
  Eigen::MatrixXd A(2, 2);
  A << 0, 1, -4, -0.4;
  const auto modes = analysis::ModalAnalysis(A);
  ASSERT_EQ(modes.size(), 1u);
  EXPECT_NEAR(modes[0].eigenvalue.imag(), std::sqrt(3.96), 1e-12);
  EXPECT_NEAR(modes[0].damping_ratio, 0.1, 1e-12);
  EXPECT_NEAR(modes[0].natural_frequency_hz, 2 / (2 * M_PI), 1e-12);
}

}  // namespace
}  // namespace mechflow::cli::modes_test
