// `mechflow help TYPE` prints a block type's or a diagram element's
// reference from the tables the loader checks against; an unknown topic is
// bad input (exit 2) with the nearest topic.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/cli/mechflow_command.h"

namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::Not;
using ::testing::StartsWith;
using mechflow::testing::RunMechflow;

TEST(HelpTopicsTest, ABlockTypeShowsItsPortsAndParameters) {
  const auto help = RunMechflow("help first_order_lag");
  EXPECT_EQ(help.exit_code, 0) << help.err;
  EXPECT_THAT(help.out, AllOf(StartsWith("block type first_order_lag: T y' + y = K u"), HasSubstr("inputs: u\n"),
                              HasSubstr("outputs: y\n"),
                              HasSubstr("  time_constant       (required) time constant T [s], > 0")));
  // a table read from a file decides its ports
  EXPECT_THAT(RunMechflow("help motion_table").out, HasSubstr("ports: they follow its parameters"));
}

TEST(HelpTopicsTest, AnElementShowsEveryTypesAttributesWithUnitsAndDefaults) {
  const auto help = RunMechflow("help force");
  EXPECT_EQ(help.exit_code, 0) << help.err;
  EXPECT_THAT(help.out, AllOf(StartsWith("<force>: "), HasSubstr("type=\"linear\": -c (x - x0) - d v + f0"),
                              HasSubstr("  c                   (default 0, [N/m]) stiffness"),
                              HasSubstr("type=\"elastic_friction2\""), HasSubstr("  body1               (required)")));
  EXPECT_THAT(RunMechflow("help solver").out, HasSubstr("  t_end               (default 1, [s]) end time"));
}

TEST(HelpTopicsTest, HelpListsTheTopicsAndRefusesAnUnknownOne) {
  const auto list = RunMechflow("help");
  EXPECT_EQ(list.exit_code, 0);
  EXPECT_THAT(list.out, AllOf(HasSubstr("Block types (mechflow help TYPE):\n"), HasSubstr("first_order_lag"),
                              HasSubstr("Diagram elements (mechflow help TAG):\n"), HasSubstr("joint_force")));
  const auto bad = RunMechflow("help forse");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_THAT(bad.err, HasSubstr("no help topic 'forse' (did you mean 'force'?)"));
  EXPECT_THAT(bad.out, Not(HasSubstr("<force>")));
  EXPECT_EQ(RunMechflow("help run").exit_code, 0);
}

}  // namespace
