// The simulator's run policies that have logic of their own (blocks/solver/):
// the limit on a crossing refiring at one instant, when repeated solver
// failures restart the method, how callback failures turn into CVODE's
// flags, and the decimal output grid.
#include <cmath>
#include <string>

#include <cvode/cvode.h>
#include <gtest/gtest.h>

#include "blocks/solver/callback_failures.h"
#include "blocks/solver/grid_time.h"
#include "blocks/solver/refiring_limit.h"
#include "blocks/solver/run_failure.h"

namespace mechflow::blocks {
namespace {

constexpr int kLimit = RefiringLimit::kMaxEventsPerInstant;

TEST(RefiringLimitTest, FailsOnTheFiringPastTheLimitAtOneInstant) {
  RefiringLimit limit;
  limit.Reset(2);
  // CVODE locates each refiring a hair after the last
  double t = 1.0;
  for (int k = 0; k < kLimit; ++k, t += 1e-12) EXPECT_TRUE(limit.Fire(0, t)) << "firing " << k + 1;
  EXPECT_FALSE(limit.Fire(0, t));
  // the other crossing counts on its own
  EXPECT_TRUE(limit.Fire(1, t));
}

TEST(RefiringLimitTest, AFiringLaterThanAnInstantStartsAFreshCount) {
  RefiringLimit limit;
  limit.Reset(1);
  double t = 2.0;
  for (int k = 0; k < kLimit; ++k, t += 1e-12) ASSERT_TRUE(limit.Fire(0, t));
  t += 2.0 * RefiringLimit::kInstant * t;  // past one instant at this |t|
  for (int k = 0; k < kLimit; ++k, t += 1e-12) EXPECT_TRUE(limit.Fire(0, t)) << "firing " << k + 1;
  EXPECT_FALSE(limit.Fire(0, t));
}

TEST(RefiringLimitTest, TheInstantGrowsWithTime) {
  // at t = 1e4 s one instant is 1e-5 s: firings 1e-6 s apart are one instant
  RefiringLimit limit;
  limit.Reset(1);
  double t = 1e4;
  for (int k = 0; k < kLimit; ++k, t += 1e-6) ASSERT_TRUE(limit.Fire(0, t));
  EXPECT_FALSE(limit.Fire(0, t));
  // near t = 0 one instant is kInstant itself: 1e-6 s apart are separate
  limit.Reset(1);
  t = 0.0;
  for (int k = 0; k < 2 * kLimit; ++k, t += 1e-6) EXPECT_TRUE(limit.Fire(0, t)) << "firing " << k + 1;
}

TEST(RefiringLimitTest, ResetForgetsEarlierFirings) {
  RefiringLimit limit;
  limit.Reset(1);
  for (int k = 0; k < kLimit; ++k) ASSERT_TRUE(limit.Fire(0, 3.0));
  limit.Reset(1);
  EXPECT_TRUE(limit.Fire(0, 3.0));
}

TEST(RestartPolicyTest, RestartsAfterRepeatedFailuresOnceEnoughStepsWereTaken) {
  const long enough = RestartPolicy::kRestartSteps;
  EXPECT_TRUE(RestartPolicy::Restarts(CV_ERR_FAILURE, false, enough));
  EXPECT_TRUE(RestartPolicy::Restarts(CV_CONV_FAILURE, false, enough + 1000));
  // a dead end fails again sooner: the run ends
  EXPECT_FALSE(RestartPolicy::Restarts(CV_ERR_FAILURE, false, enough - 1));
  EXPECT_FALSE(RestartPolicy::Restarts(CV_CONV_FAILURE, false, 0));
}

TEST(RestartPolicyTest, NeverAfterACallbackFailedOrForOtherFlags) {
  const long many = 10 * RestartPolicy::kRestartSteps;
  EXPECT_FALSE(RestartPolicy::Restarts(CV_ERR_FAILURE, true, many));
  EXPECT_FALSE(RestartPolicy::Restarts(CV_CONV_FAILURE, true, many));
  for (const int flag : {CV_TOO_MUCH_WORK, CV_RHSFUNC_FAIL, CV_TOO_CLOSE, CV_LSETUP_FAIL})
    EXPECT_FALSE(RestartPolicy::Restarts(flag, false, many)) << flag;
}

TEST(CallbackFailuresTest, RecoverableUntilTooManyThenFinal) {
  CallbackFailures failures;
  EXPECT_FALSE(failures.any());
  for (int k = 0; k < CallbackFailures::kMaxRecoverable; ++k) EXPECT_EQ(failures.Recoverable("x"), 1) << k;
  EXPECT_EQ(failures.Recoverable("the last"), -1);
  EXPECT_TRUE(failures.any());
  EXPECT_EQ(failures.reason(), "the last");
  failures.Reset();
  EXPECT_FALSE(failures.any());
  EXPECT_EQ(failures.Recoverable("again"), 1);
}

TEST(CallbackFailuresTest, RetriesAreNotCountedAndBugsAreFinal) {
  CallbackFailures failures;
  for (int k = 0; k < 3 * CallbackFailures::kMaxRecoverable; ++k) ASSERT_EQ(failures.Retry("not finite"), 1);
  EXPECT_EQ(failures.Recoverable("thrown"), 1);
  EXPECT_EQ(failures.Final("outside its pattern"), -1);
  EXPECT_EQ(failures.reason(), "outside its pattern");
}

TEST(GridTimeTest, RoundedProductsReadAsTheirDecimals) {
  EXPECT_NE(47 * 0.01, 0.47);  // the product rounds ...
  EXPECT_EQ(DecimalGridTime(47 * 0.01), 0.47);  // ... the row is taken at 0.47
  // a grid of its own (k / 3) is no rounding of a decimal: kept
  EXPECT_EQ(DecimalGridTime(1.0 / 3.0), 1.0 / 3.0);
  EXPECT_EQ(DecimalGridTime(0.0), 0.0);
}

TEST(GridTimeTest, OutputTimesComeFromTheirIndexAndStopAtTheEnd) {
  const OutputGrid grid(0.0, 0.01, 0.475);
  EXPECT_EQ(grid.Time(0), 0.0);
  EXPECT_EQ(grid.Time(47), 0.47);
  EXPECT_EQ(grid.Time(48), 0.475);
  // no drift: the millionth time is a million intervals on
  const OutputGrid long_grid(10.0, 0.1, 1e9);
  EXPECT_EQ(long_grid.Time(1'000'000), 100010.0);
}

}  // namespace
}  // namespace mechflow::blocks
