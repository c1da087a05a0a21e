# Sources of the scripting layer.
set(MECHFLOW_SCRIPTING_SOURCES
  scripting/lua_state.cc
)
