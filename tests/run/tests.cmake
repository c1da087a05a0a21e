# Tests of run/.
mechflow_test(run_model_test unit tests/run/model_test.cc)
