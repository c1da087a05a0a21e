# Tests of analysis/.
mechflow_test(force_analysis_test unit tests/analysis/force_analysis_test.cc)
mechflow_test(spectrum_test unit tests/analysis/spectrum_test.cc)
