// run::Batch: runs on threads give what single runs give, bit for bit, by
// index; a run that throws is an outcome, not an exception.
#include "run/batch.h"

#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "diagrams/xml_reader.h"
#include "run/sinks.h"

namespace mechflow::run {
namespace batch_test {

std::string Example(const std::string& name) { return std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/" + name; }

TEST(RunBatch, ThreadsGiveSingleRuns) {
  const std::string file = Example("damped_oscillator_blocks.xml");
  Batch batch({{diagrams::ReadDiagramFile(file), {}}}, 2);
  std::vector<BatchJob> jobs;
  for (int i = 0; i < 6; ++i) {
    BatchJob job;
    job.set = {{"beta", 0.05 * (i + 1)}};
    job.options.times = {0.5, 1.0, 2.25};
    job.options.log = std::vector<std::string>{"x.y"};
    jobs.push_back(job);
  }
  jobs.push_back(jobs.front());
  jobs.back().set = {{"no_such", 1.0}};
  const std::vector<BatchOutcome> done = batch.Run(jobs);
  for (int again = 0; again < 2; ++again) {  // the workers' models serve a second round alike
    const std::vector<BatchOutcome> second = again ? batch.Run(jobs) : done;
    for (int i = 0; i < 6; ++i) {
      Model single(file);
      single.Set("beta", 0.05 * (i + 1));
      MemorySink rows;
      single.Run(jobs[i].options, &rows);
      EXPECT_EQ(second[i].columns, rows.columns()) << "run " << i;
      ASSERT_EQ(second[i].columns.size(), 2u);
      EXPECT_EQ(second[i].columns[0], (std::vector<double>{0.5, 1.0, 2.25}));
    }
    EXPECT_EQ(second[6].result.status, Status::kFailed);
    EXPECT_THAT(second[6].result.reason, ::testing::HasSubstr("no_such"));
  }
  EXPECT_EQ(batch.runs(), 14);
}

}  // namespace batch_test
}  // namespace mechflow::run
