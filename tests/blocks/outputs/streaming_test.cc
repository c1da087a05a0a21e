// Results streamed as they are computed (blocks/outputs/results.h): each row reaches
// the sink when it is recorded, and only the columns asked for stay in
// memory, so a long run's memory does not grow with its rows.

#include <cmath>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "tests/blocks/block_test_util.h"

namespace mechflow::blocks {
namespace {

using testing::Blocks;
using testing::MakeBlock;

// Keeps what it was given and what the run had recorded by then.
class RecordingSink final : public RowSink {
 public:
  explicit RecordingSink(const Results* results) : results_(results) {}
  void WriteRow(const double* values, int count) override {
    rows.emplace_back(values, values + count);
    recorded_when_written.push_back(results_->num_rows());
  }
  std::vector<std::vector<double>> rows;
  std::vector<int> recorded_when_written;

 private:
  const Results* results_;
};

TEST(StreamingTest, RowsReachTheSinkAsTheyAreRecordedAndOnlyKeptColumnsStay) {
  DiagramBuilder builder;
  builder.AddBlock(MakeBlock("sine", "s"));
  builder.AddBlock(MakeBlock("integrator", "i"));
  builder.Connect("s", "i");
  const auto diagram = builder.Build();
  SolverOptions options = testing::Options(2.0, 0.01);
  Simulator sim(*diagram, options, {diagram->ResolveSignal("s.y"), diagram->ResolveSignal("i.y")});
  RecordingSink sink(&sim.results());
  sim.StreamRows(&sink, {2});  // keep i.y (and time)
  ASSERT_TRUE(sim.Run().ok);

  ASSERT_EQ(sink.rows.size(), 201u);
  EXPECT_EQ(sim.results().num_rows(), 201);
  for (std::size_t r = 0; r < sink.rows.size(); ++r) {
    EXPECT_EQ(sink.recorded_when_written[r], static_cast<int>(r) + 1);  // written when recorded, not at the end
    EXPECT_NEAR(sink.rows[r][0], 0.01 * r, 1e-12);
  }
  const std::vector<double> kept = sim.results().Column(2);
  ASSERT_EQ(kept.size(), 201u);
  EXPECT_EQ(kept.back(), sink.rows.back()[2]);
  EXPECT_THROW(sim.results().Column(1), std::logic_error);  // not kept
  EXPECT_THROW(sim.results().at(0, 1), std::logic_error);
  // ranges are kept for every column: s = sin(2 pi t) peaks at t = 0.25
  EXPECT_DOUBLE_EQ(sim.results().range(1).max, 1.0);
  EXPECT_NEAR(sim.results().range(1).max_time, 0.25, 1e-12);
}

}  // namespace
}  // namespace mechflow::blocks
