# Tests of blocks/.
mechflow_test(simulator_test unit tests/blocks/simulator_test.cc)
mechflow_test(library_test unit tests/blocks/library_test.cc)
mechflow_test(no_allocation_test unit tests/blocks/no_allocation_test.cc)
