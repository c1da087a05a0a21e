# Tests of diagrams/.
mechflow_test(loader_test unit tests/diagrams/loader_test.cc)
mechflow_test(mechanism_loader_test unit tests/diagrams/mechanism_loader_test.cc)
mechflow_test(variants_test unit tests/diagrams/variants_test.cc)
mechflow_test(bad_input_test unit tests/diagrams/bad_input_test.cc)
mechflow_test(large_input_growth_test unit tests/diagrams/large_input_growth_test.cc)
mechflow_test(units_test unit tests/diagrams/units_test.cc)
mechflow_test(element_table_test unit tests/diagrams/element_table_test.cc)
mechflow_test(instances_test unit tests/diagrams/instances_test.cc)
