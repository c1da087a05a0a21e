# Tests of scripting/, one executable per source file.
mechflow_test(lua_state_test unit tests/scripting/lua_state_test.cc)
mechflow_test(identifiers_test unit tests/scripting/identifiers_test.cc)
mechflow_test(compiled_expression_test unit tests/scripting/compiled_expression_test.cc)
mechflow_test(expression_block_test unit tests/scripting/expression_block_test.cc)
mechflow_test(time_function_test unit tests/scripting/time_function_test.cc)
mechflow_test(sandbox_test unit tests/scripting/sandbox_test.cc)
mechflow_test(control_script_test unit tests/scripting/control_script_test.cc)
mechflow_test(lua_block_test unit tests/scripting/lua_block_test.cc)
