# Tests of analysis/.
mechflow_test(force_analysis_test unit tests/analysis/force_analysis_test.cc)
mechflow_test(spectrum_test unit tests/analysis/spectrum_test.cc)
mechflow_test(linearization_test unit tests/analysis/linearization_test.cc)
mechflow_test(equilibrium_modes_test unit tests/analysis/equilibrium_modes_test.cc)
mechflow_test(fit_test unit tests/analysis/fit_test.cc)
mechflow_test(fit_stick_slip_test unit tests/analysis/fit_stick_slip_test.cc)
