// The damper chain (diagrams/examples/damper_chain.xml) is built from an
// array of friction-damper subsystems; tests/regression/data/damper_chain_flat.xml
// is the same model written out block by block. The loader's flattening must
// give the very same model: the two runs write byte-identical CSVs. And the
// example does what it is for: every stage sticks to the belt and slips.

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/cli/mechflow_command.h"

namespace mechflow {
namespace {

namespace fs = std::filesystem;

// Runs `diagram` with the mechflow command into a fresh folder; its CSV.
std::string RunToCsv(const std::string& diagram, const std::string& folder) {
  const fs::path out = fs::path(::testing::TempDir()) / folder;
  fs::remove_all(out);
  const auto run = testing::RunMechflow("run " + diagram + " --quiet --no-animate --out " + out.string());
  EXPECT_EQ(run.exit_code, 0) << run.err;
  return testing::ReadFile(out / "damper_chain.csv");
}

// The CSV's columns by their header labels.
std::vector<std::vector<double>> Columns(const std::string& csv, std::vector<std::string>* labels) {
  std::istringstream in(csv);
  std::string line, cell;
  std::getline(in, line);
  for (std::istringstream header(line); std::getline(header, cell, ',');) labels->push_back(cell);
  std::vector<std::vector<double>> columns(labels->size());
  while (std::getline(in, line)) {
    std::istringstream row(line);
    for (std::size_t c = 0; c < columns.size() && std::getline(row, cell, ','); ++c)
      columns[c].push_back(std::stod(cell));
  }
  return columns;
}

TEST(DamperChainTest, SubsystemArrayWritesTheCsvOfTheFlatModel) {
  const std::string example = RunToCsv(std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/damper_chain.xml",
                                       "damper_chain_parts");
  const std::string flat = RunToCsv(std::string(MECHFLOW_SOURCE_DIR) + "/tests/regression/data/damper_chain_flat.xml",
                                    "damper_chain_flat");
  ASSERT_GT(example.size(), 100000u);  // 5001 rows of 10 columns
  EXPECT_TRUE(example == flat) << "the CSVs differ (sizes " << example.size() << " and " << flat.size() << ")";

  std::vector<std::string> labels;
  const auto columns = Columns(example, &labels);
  ASSERT_EQ(labels.size(), 10u);
  const double v_belt = 0.2;
  for (int stage = 0; stage < 3; ++stage) {
    const auto& v = columns[4 + stage];
    ASSERT_EQ(labels[4 + stage], "v" + std::to_string(stage));
    // stuck: riding with the belt; slipping back: moving against it
    int stuck = 0, slipping = 0, slips = 0;
    bool was_stuck = false;
    for (const double value : v) {
      const bool is_stuck = std::abs(value - v_belt) < 1e-4;
      stuck += is_stuck;
      slipping += value < 0;
      slips += was_stuck && !is_stuck;
      was_stuck = is_stuck;
    }
    EXPECT_GT(stuck, 500) << "stage " << stage;
    EXPECT_GT(slipping, 100) << "stage " << stage;
    EXPECT_GE(slips, 2) << "stage " << stage;
  }
}

}  // namespace
}  // namespace mechflow
