# Tests of regression/.
mechflow_test(examples_test regression tests/regression/examples_test.cc)
