// Fuzz target: a table file's text through the readers of the `table`,
// `lookup`, `motion_table` (points of one argument) and `lookup_2d` (a grid
// with a corner label) blocks.

#include <vector>

#include "blocks/library/lookup.h"
#include "blocks/library/table.h"
#include "tests/fuzz/fuzz_target.h"

namespace {

void ReadTables(const std::string& text) {
  using namespace mechflow::blocks;
  std::vector<double> xs, ys;
  try {
    ReadTableCsv(text, "fuzz.csv", &xs, &ys);
  } catch (const mechflow::InputError&) {
  }
  std::vector<double> x, y;
  std::vector<std::vector<double>> values;
  ReadTable2DCsv(text, "fuzz.csv", &x, &y, &values);
}

}  // namespace

MECHFLOW_FUZZ_TARGET(ReadTables)
