# Tests of cli/.
mechflow_test(cli_test unit tests/cli/cli_test.cc)
