// Plots of long runs: drawn from a min/max envelope per bin of time (at most
// a pixel column wide) instead of every row, with every extreme kept. The
// envelope is checked against the rows it was made of: each bin's min and
// max are exactly the smallest and largest of its rows' values.

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli/plot_envelope.h"
#include "tests/cli/mechflow_command.h"

namespace mechflow::plot_envelope_test {  // names of its own: the files of its folder are compiled together
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;
using Rows = std::vector<std::vector<double>>;

fs::path Dir(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("plot_envelope_" + std::to_string(getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// The numbers of a CSV text after its header (shortest round-trip text, so
// strtod gives back the very values).
Rows ParseCsv(const std::string& text, std::string* header = nullptr) {
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  if (header) *header = line;
  Rows rows;
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::istringstream fields(line);
    for (std::string field; std::getline(fields, field, ',');) row.push_back(std::strtod(field.c_str(), nullptr));
    rows.push_back(row);
  }
  return rows;
}

// `envelope` (rows,t_first,t_last,time, then min,max per column) against the
// results rows `csv`: its bins take the rows in order, and column `c`'s min
// and max (at envelope column min_column[c], 0-based) are exactly the
// smallest and largest value of c among the bin's rows.
void ExpectEnvelopeOf(const Rows& csv, const Rows& envelope, const std::vector<int>& columns,
                      const std::vector<int>& min_column) {
  std::size_t next = 0;
  for (const std::vector<double>& bin : envelope) {
    const auto n = static_cast<std::size_t>(bin[0]);
    ASSERT_GE(n, 1u);
    ASSERT_LE(next + n, csv.size());
    EXPECT_EQ(bin[1], csv[next][0]);
    EXPECT_EQ(bin[2], csv[next + n - 1][0]);
    EXPECT_TRUE(bin[1] <= bin[3] && bin[3] <= bin[2]);
    for (std::size_t k = 0; k < columns.size(); ++k) {
      double lo = csv[next][columns[k]], hi = lo;
      for (std::size_t r = next; r < next + n; ++r) {
        lo = std::min(lo, csv[r][columns[k]]);
        hi = std::max(hi, csv[r][columns[k]]);
      }
      ASSERT_EQ(bin[min_column[k]], lo) << "bin from row " << next << ", column " << columns[k];
      ASSERT_EQ(bin[min_column[k] + 1], hi) << "bin from row " << next << ", column " << columns[k];
    }
    next += n;
  }
  EXPECT_EQ(next, csv.size());  // every row in a bin
}

struct Collect : blocks::RowSink {
  Rows rows;
  void WriteRow(const double* values, int count) override { rows.emplace_back(values, values + count); }
};

// 100000 rows of a fast oscillation with single-row spikes, and a slow one.
Rows Signals(int rows, double dt) {
  Rows out;
  for (int k = 0; k < rows; ++k) {
    const double t = k * dt;
    double x = std::sin(2 * M_PI * 37 * t) * (1 + 0.1 * std::sin(t));
    if (k % 7919 == 5) x = (k % 2 ? 5.0 : -4.0) + 1e-3 * k;  // a spike one row wide
    out.push_back({t, x, std::cos(2 * M_PI * 0.3 * t)});
  }
  return out;
}

TEST(PlotEnvelopeTest, EachBinHoldsTheExactExtremesOfItsRows) {
  const Rows rows = Signals(100000, 1e-4);
  Collect next;
  cli::PlotEnvelope envelope({1, 2}, {1, 2}, 10.0, &next);
  for (const auto& row : rows) envelope.WriteRow(row.data(), 3);
  EXPECT_EQ(next.rows, rows);  // passed on as they came
  ASSERT_TRUE(envelope.worthwhile());
  std::string header;
  const Rows bins = ParseCsv(envelope.Csv({"time", "x", "y"}), &header);
  EXPECT_EQ(header, "rows,t_first,t_last,time,x min,x max,y min,y max");
  EXPECT_EQ(envelope.MinColumn(1), 5);
  EXPECT_EQ(envelope.MinColumn(2), 7);
  // the run's first and last rows are bins of their own: the plot spans it
  EXPECT_EQ(bins.front()[0], 1);
  EXPECT_EQ(bins.back()[0], 1);
  EXPECT_EQ(bins.back()[3], rows.back()[0]);
  EXPECT_GE(bins.size(), cli::PlotEnvelope::kBins / 2u);
  EXPECT_LE(bins.size(), cli::PlotEnvelope::kBins + 2u);
  ExpectEnvelopeOf(rows, bins, {1, 2}, {4, 6});
}

TEST(PlotEnvelopeTest, ARunEndingEarlyStillFillsHalfTheBins) {
  const Rows rows = Signals(30000, 1e-3);  // 30 s of a run meant to last 3000 s
  cli::PlotEnvelope envelope({1}, {}, 3000.0, nullptr);
  for (const auto& row : rows) envelope.WriteRow(row.data(), 3);
  const Rows bins = ParseCsv(envelope.Csv({"time", "x", "y"}));
  EXPECT_GE(bins.size(), cli::PlotEnvelope::kBins / 2u);
  ExpectEnvelopeOf(rows, bins, {1}, {4});
}

TEST(PlotEnvelopeTest, RowsAtOneInstantAndShortRuns) {
  // events: several rows at one time; a bin still holds consecutive rows
  Rows rows = Signals(20000, 1e-3);
  for (int k = 100; k < 20000; k += 97) rows[k][0] = rows[k - 1][0];
  cli::PlotEnvelope envelope({1, 2}, {}, 20.0, nullptr);
  for (const auto& row : rows) envelope.WriteRow(row.data(), 3);
  ExpectEnvelopeOf(rows, ParseCsv(envelope.Csv({"time", "x", "y"})), {1, 2}, {4, 6});
  // a short run is drawn from its rows
  cli::PlotEnvelope short_run({1}, {}, 20.0, nullptr);
  for (int k = 0; k < 2 * cli::PlotEnvelope::kBins; ++k) short_run.WriteRow(rows[k].data(), 3);
  EXPECT_FALSE(short_run.worthwhile());
}

TEST(PlotEnvelopeTest, XYRowsKeepEveryExtremeOfBothCoordinates) {
  const Rows rows = Signals(100000, 1e-4);
  cli::PlotEnvelope envelope({1, 2}, {1, 2}, 10.0, nullptr);
  for (const auto& row : rows) envelope.WriteRow(row.data(), 3);
  std::string header;
  const Rows kept = ParseCsv(envelope.XYCsv({"time", "x", "y"}), &header);
  EXPECT_EQ(header, "time,x,y");
  EXPECT_EQ(envelope.XYColumn(1), 2);
  EXPECT_EQ(envelope.XYColumn(2), 3);
  EXPECT_LE(kept.size(), 4u * cli::PlotEnvelope::kBins + 2);
  EXPECT_EQ(kept.front(), rows.front());
  EXPECT_EQ(kept.back(), rows.back());
  // rows of the run, in time order (times are distinct here)
  std::size_t at = 0;
  for (const auto& row : kept) {
    while (at < rows.size() && rows[at][0] != row[0]) ++at;
    ASSERT_LT(at, rows.size()) << "row at t = " << row[0] << " not among the run's, or out of order";
    EXPECT_EQ(row, rows[at]);
  }
  // every spike (a row-wide extreme of x) is kept
  for (std::size_t k = 5; k < rows.size(); k += 7919)
    EXPECT_TRUE(std::find(kept.begin(), kept.end(), rows[k]) != kept.end()) << "spike at row " << k;
}

// A diagram of a 37 Hz oscillation and a slow one with an x-y panel, `t_end` long at 1 ms.
void WriteDiagram(const fs::path& file, const std::string& t_end) {
  std::ofstream(file) << "<diagram name='d'><identifiers><identifier name='f' value='37'/></identifiers><blocks>"
                         "<block type='sine' name='s' frequency='f'/><block type='sine' name='c' frequency='0.3' "
                         "phase='1.5707963267948966'/></blocks><solver t_end='"
                      << t_end << "'/><output interval='1e-3' plot='d.png'><log signal='s.y' group='fast'/>"
                                  "<log signal='c.y' group='slow'/><xy title='phase' curves='s.y:c.y'/></output>"
                                  "</diagram>";
}

TEST(PlotEnvelopeTest, ALongRunIsDrawnFromItsEnvelopeAShortOneFromItsRows) {
  const fs::path dir = Dir("run");
  WriteDiagram(dir / "d.xml", "20");
  const auto run = testing::RunMechflow("run " + (dir / "d.xml").string() + " --out " + (dir / "out").string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::string header;
  const Rows csv = ParseCsv(testing::ReadFile(dir / "out" / "d.csv"));
  ASSERT_EQ(csv.size(), 20001u);
  const Rows bins = ParseCsv(testing::ReadFile(dir / "out" / "d.png.envelope.csv"), &header);
  EXPECT_EQ(header, "rows,t_first,t_last,time,s.y min,s.y max,c.y min,c.y max");
  ExpectEnvelopeOf(csv, bins, {1, 2}, {4, 6});
  const std::string script = testing::ReadFile(dir / "out" / "d.png.gp");
  EXPECT_THAT(script, HasSubstr("'d.png.envelope.csv' using 4:5:6 every ::1 with filledcurves"));
  EXPECT_THAT(script, HasSubstr("'d.png.xy.csv' using 2:3 every ::1 with lines"));
  EXPECT_THAT(script, Not(HasSubstr("'d.csv'")));
  EXPECT_THAT(script, HasSubstr("20001 rows, drawn as their min and max per pixel column"));

  WriteDiagram(dir / "d.xml", "2");
  const auto short_run = testing::RunMechflow("run " + (dir / "d.xml").string() + " --out " + (dir / "out").string());
  ASSERT_EQ(short_run.exit_code, 0) << short_run.err;
  const std::string plain = testing::ReadFile(dir / "out" / "d.png.gp");
  EXPECT_THAT(plain, HasSubstr("plot 'd.csv' using 1:2 every ::1 with lines lw 1.5 lc rgb '#1f77b4' dt 1 title 's.y'\n"));
  EXPECT_THAT(plain, Not(HasSubstr("envelope")));
}

TEST(PlotEnvelopeTest, ASweepOverlaysItsLongRunsEnvelopes) {
  const fs::path dir = Dir("sweep");
  WriteDiagram(dir / "d.xml", "20");
  const std::string command = "sweep " + (dir / "d.xml").string() + " --vary f=37,41 --jobs 2 --out " +
                              (dir / "out").string();
  const auto sweep = testing::RunMechflow(command);
  ASSERT_EQ(sweep.exit_code, 0) << sweep.err;
  const Rows csv = ParseCsv(testing::ReadFile(dir / "out" / "d.run2.f=41.csv"));
  ExpectEnvelopeOf(csv, ParseCsv(testing::ReadFile(dir / "out" / "d.run2.f=41.envelope.csv")), {1, 2}, {4, 6});
  const std::string script = testing::ReadFile(dir / "out" / "d.sweep.png.gp");
  EXPECT_THAT(script, HasSubstr("'d.run1.f=37.envelope.csv' using 4:5:6 every ::1 with filledcurves"));
  EXPECT_THAT(script, HasSubstr("'d.run2.f=41.envelope.csv' using 4:7:8 every ::1 with filledcurves"));
  // a short sweep in the same folder leaves no envelope of the long one to be drawn
  WriteDiagram(dir / "d.xml", "2");
  ASSERT_EQ(testing::RunMechflow(command).exit_code, 0);
  EXPECT_FALSE(fs::exists(dir / "out" / "d.run1.f=37.envelope.csv"));
  EXPECT_THAT(testing::ReadFile(dir / "out" / "d.sweep.png.gp"), Not(HasSubstr("envelope")));
}

}  // namespace
}  // namespace mechflow::plot_envelope_test
