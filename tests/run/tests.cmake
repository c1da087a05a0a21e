# Tests of run/.
mechflow_test(run_model_test unit tests/run/model_test.cc)
mechflow_test(run_batch_test unit tests/run/batch_test.cc)
mechflow_test(run_session_test unit tests/run/session_test.cc)
