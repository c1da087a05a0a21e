# Tests of regression/.
mechflow_test(examples_test regression tests/regression/examples_test.cc)
mechflow_test(mechanism_examples_test regression tests/regression/mechanism_examples_test.cc)
mechflow_test(friction_examples_test regression tests/regression/friction_examples_test.cc)
mechflow_test(tension_mechanism_test regression tests/regression/tension_mechanism_test.cc)
mechflow_test(contact_test regression tests/regression/contact_test.cc)
mechflow_test(bushing_test regression tests/regression/bushing_test.cc)
mechflow_test(gearing_test regression tests/regression/gearing_test.cc)
