# Tests of cli/.
mechflow_test(cli_test unit tests/cli/cli_test.cc)
mechflow_test(modes_test unit tests/cli/modes_test.cc)
mechflow_test(modes_command_test unit tests/cli/modes_command_test.cc)
mechflow_test(figures_test unit tests/cli/figures_test.cc)
