# Tests of blocks/.
mechflow_test(simulator_test unit tests/blocks/simulator_test.cc)
mechflow_test(library_test unit tests/blocks/library_test.cc)
