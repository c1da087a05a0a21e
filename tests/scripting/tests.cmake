# Tests of scripting/.
mechflow_test(scripting_test unit tests/scripting/scripting_test.cc)
