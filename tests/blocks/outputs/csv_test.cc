// CSV as tools read it (spreadsheets, pandas and gnuplot read our files as they
// are): numbers in the shortest form that
// reads back to the same double, no negative zero; fields quoted per RFC 4180.
#include "blocks/outputs/csv.h"

#include <cmath>
#include <cstdlib>
#include <random>
#include <sstream>

#include <gtest/gtest.h>

#include "blocks/outputs/results.h"

namespace mechflow::blocks {
namespace {

TEST(CsvTest, NumbersAreShortestAndReadBackExactly) {
  EXPECT_EQ(CsvNumber(0.1), "0.1");
  EXPECT_EQ(CsvNumber(-0.0), "0");
  EXPECT_EQ(CsvNumber(1e-300), "1e-300");
  EXPECT_EQ(CsvNumber(2.0), "2");
  std::mt19937_64 random(3);
  std::uniform_real_distribution<double> exponent(-300, 300), mantissa(-1, 1);
  for (int i = 0; i < 10000; ++i) {
    const double v = mantissa(random) * std::pow(10.0, exponent(random));
    EXPECT_EQ(std::strtod(CsvNumber(v).c_str(), nullptr), v);
  }
}

TEST(CsvTest, ResultsQuoteTheirHeaderAndWriteNoNegativeZero) {
  Results r({"x, m", "say \"hi\"", "plain"});
  const double row[] = {0.0, -0.0, 0.30000000000000004, 1.5};
  r.AddRow(row);
  std::ostringstream out;
  r.WriteCsv(out);
  EXPECT_EQ(out.str(), "time,\"x, m\",\"say \"\"hi\"\"\",plain\n0,0,0.30000000000000004,1.5\n");
}

}  // namespace
}  // namespace mechflow::blocks
