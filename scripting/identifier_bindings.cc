#include "scripting/identifier_bindings.h"

#include <string_view>
#include <unordered_set>

#include <lua.hpp>

#include "scripting/identifiers.h"

namespace mechflow::scripting {
namespace {

constexpr const char* kBindingsKey = "mechflow.identifier_bindings";

// Pushes the registry's table of bound functions, creating it (weak keys) once.
void PushBindings(lua_State* L) {
  if (lua_getfield(L, LUA_REGISTRYINDEX, kBindingsKey) == LUA_TTABLE) return;
  lua_pop(L, 1);
  lua_newtable(L);
  lua_newtable(L);
  lua_pushliteral(L, "k");
  lua_setfield(L, -2, "__mode");
  lua_setmetatable(L, -2);
  lua_pushvalue(L, -1);
  lua_setfield(L, LUA_REGISTRYINDEX, kBindingsKey);
}

}  // namespace

void BindIdentifiers(lua_State* L, int index) {
  index = lua_absindex(L, index);
  PushBindings(L);
  lua_pushvalue(L, index);
  lua_pushboolean(L, 1);
  lua_rawset(L, -3);
  lua_pop(L, 1);
}

int RebindIdentifiers(lua_State* L, const IdentifierTable& identifiers, const std::vector<std::string>& changed) {
  if (changed.empty()) return 0;
  // a run's start rebinds every identifier: a hash set keeps that linear
  const std::unordered_set<std::string_view> wanted(changed.begin(), changed.end());
  int set = 0;
  PushBindings(L);
  lua_pushnil(L);
  while (lua_next(L, -2) != 0) {
    lua_pop(L, 1);  // the value; the function (key) stays for lua_next
    for (int i = 1; const char* name = lua_getupvalue(L, -1, i); ++i) {
      lua_pop(L, 1);
      const int id = wanted.count(name) ? identifiers.FindLowerCase(name) : -1;
      if (id < 0) continue;
      lua_pushnumber(L, identifiers.value(id));
      lua_setupvalue(L, -2, i);
      ++set;
    }
  }
  lua_pop(L, 1);
  return set;
}

}  // namespace mechflow::scripting
