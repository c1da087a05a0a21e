# Tests of analysis/.
mechflow_test(force_analysis_test unit tests/analysis/force_analysis_test.cc)
