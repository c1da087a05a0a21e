# Sources of the scripting layer.
set(MECHFLOW_SCRIPTING_SOURCES
  scripting/compiled_expression.cc
  scripting/expression_block.cc
  scripting/global_reads.cc
  scripting/identifier_bindings.cc
  scripting/identifier_block.cc
  scripting/control_script.cc
  scripting/identifiers.cc
  scripting/lua_block.cc
  scripting/lua_guards.cc
  scripting/lua_state.cc
  scripting/jet_expression.cc
  scripting/jet_expression_compiler.cc
)
