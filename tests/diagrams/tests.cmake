# Tests of diagrams/.
mechflow_test(loader_test unit tests/diagrams/loader_test.cc)
