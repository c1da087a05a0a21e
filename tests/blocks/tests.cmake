# Tests of blocks/.
mechflow_test(simulator_test unit tests/blocks/simulator_test.cc)
