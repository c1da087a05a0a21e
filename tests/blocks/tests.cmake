# Tests of blocks/.
mechflow_test(simulator_test unit tests/blocks/simulator_test.cc)
mechflow_test(library_test unit tests/blocks/library_test.cc)
mechflow_test(no_allocation_test unit tests/blocks/no_allocation_test.cc)
mechflow_test(discontinuities_test unit tests/blocks/discontinuities_test.cc)
mechflow_test(integrator_test unit tests/blocks/integrator_test.cc)
