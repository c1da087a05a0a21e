// run::Batch: runs on threads give what single runs give, bit for bit, by
// index; a run that throws is an outcome, not an exception.
#include "run/batch.h"

#include <csignal>
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

// A job runs with its own --set values only: what an earlier job on the
// same worker set is gone, whichever worker takes it.
TEST(RunBatch, AJobKeepsNothingOfTheJobBefore) {
  const std::string file = Example("damped_oscillator_blocks.xml");
  Batch batch({{diagrams::ReadDiagramFile(file), {}}}, 1);
  BatchJob set, plain, expression;
  set.set = {{"beta", 0.3}};
  expression.set_expressions = {{"beta", "0.15 * 2"}};
  for (BatchJob* job : {&set, &plain, &expression}) job->options.times = {0.5, 1.0, 2.25};
  const std::vector<BatchOutcome> done = batch.Run({set, plain, expression, plain});
  Model single(file);
  MemorySink rows;
  single.Run(plain.options, &rows);
  EXPECT_EQ(done[1].columns, rows.columns());
  EXPECT_EQ(done[3].columns, rows.columns());
  EXPECT_NE(done[0].columns, rows.columns());
  EXPECT_EQ(done[2].columns, done[0].columns);  // 0.15 * 2 is 0.3 exactly (doubling is)
}

// What each job without a run says of itself: a refused --set name, a flag
// already raised; a run's events named as the event log names them.
TEST(RunBatch, RefusalsAndEventNames) {
  LoadOptions free;
  free.variants = {"Free"};
  Batch batch({{diagrams::ReadDiagramFile(Example("elast_friction.xml")), free}}, 2);
  BatchJob run, unknown, interrupted;
  unknown.set = {{"no_such", 1.0}};
  volatile std::sig_atomic_t raised = SIGINT;
  interrupted.options.interrupt = &raised;
  const std::vector<BatchOutcome> done = batch.Run({run, unknown, interrupted});
  EXPECT_EQ(done[0].refused, Refusal::kNone);
  ASSERT_EQ(done[0].result.events.size(), 1u);  // the box comes to rest at 1.5 s
  ASSERT_EQ(done[0].event_names.size(), 1u);
  EXPECT_THAT(done[0].event_names[0], ::testing::StartsWith("m.friction: slip+ ends: sticks"));
  EXPECT_EQ(done[1].refused, Refusal::kInput);
  EXPECT_EQ(done[1].result.status, Status::kFailed);
  EXPECT_THAT(done[1].result.reason, ::testing::HasSubstr("no identifier named 'no_such'"));
  EXPECT_EQ(done[2].refused, Refusal::kInterrupted);
  EXPECT_EQ(done[2].result.status, Status::kInterrupted);
  EXPECT_EQ(done[2].result.reason, "not run: interrupted by SIGINT");
  EXPECT_TRUE(done[2].columns.empty());
}

}  // namespace batch_test
}  // namespace mechflow::run
