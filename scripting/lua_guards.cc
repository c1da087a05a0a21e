#include "scripting/lua_guards.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <initializer_list>

#include <lua.hpp>

#include "scripting/lua_state.h"

namespace mechflow::scripting {
namespace {

// Every function here is called by Lua and may raise a Lua error (a long
// jump): none owns a C++ object with a destructor.

// Calls the original function (upvalue 1) with this call's arguments.
int CallOriginal(lua_State* L) {
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, lua_gettop(L) - 1, LUA_MULTRET);
  return lua_gettop(L);
}

int GuardedRep(lua_State* L) {
  std::size_t length = 0, separator = 0;
  luaL_checklstring(L, 1, &length);
  const lua_Integer n = luaL_checkinteger(L, 2);
  luaL_optlstring(L, 3, "", &separator);
  if (n <= 0 || (length == 0 && separator == 0)) {
    lua_pushliteral(L, "");
    return 1;
  }
  return CallOriginal(L);
}

// table.move(a1, f, e, t [, a2]); upvalue 2: the most elements allowed.
int GuardedMove(lua_State* L) {
  const lua_Integer f = luaL_checkinteger(L, 2);
  const lua_Integer e = luaL_checkinteger(L, 3);
  const double count = static_cast<double>(e) - static_cast<double>(f) + 1.0;
  const double most = static_cast<double>(lua_tointeger(L, lua_upvalueindex(2)));
  if (count > most) {
    char text[160];
    std::snprintf(text, sizeof text, "%.6g elements are more than a table can hold under the memory limit (%.6g)",
                  count, most);
    return luaL_error(L, "table.move: %s", text);
  }
  return CallOriginal(L);
}

// The repetition items (*, +, -) of a Lua pattern, sets and escapes skipped:
// each lets the matcher backtrack over the subject once more. Optional items
// (?) are counted in *optional: each doubles the ways to match.
int Repetitions(const char* p, std::size_t size, int* optional) {
  int count = 0;
  *optional = 0;
  for (std::size_t i = 0; i < size; ++i) {
    const char c = p[i];
    if (c == '%') {
      if (i + 1 < size && p[i + 1] == 'b') ++count;  // %bxy scans for its closing character
      ++i;
    } else if (c == '[') {
      ++i;
      if (i < size && p[i] == '^') ++i;
      if (i < size && p[i] == ']') ++i;  // a leading ] is a member
      for (; i < size && p[i] != ']'; ++i)
        if (p[i] == '%') ++i;
    } else if (c == '*' || c == '+' || c == '-') {
      ++count;
    } else if (c == '?') {
      ++*optional;
    }
  }
  return count;
}

// string.find/match/gmatch/gsub(s, pattern, ...); upvalue 3: true for find,
// whose 4th argument asks for a plain search.
int GuardedPattern(lua_State* L) {
  std::size_t n = 0, m = 0;
  luaL_checklstring(L, 1, &n);
  const char* pattern = luaL_checklstring(L, 2, &m);
  const bool plain = lua_toboolean(L, lua_upvalueindex(3)) && lua_toboolean(L, 4);
  int optional = 0;
  const int repetitions = plain ? 0 : Repetitions(pattern, m, &optional);
  if (repetitions > 0 || optional > 0) {
    const bool anchored = m > 0 && pattern[0] == '^';
    const double steps = std::pow(static_cast<double>(n) + 1.0, repetitions + (anchored ? 0 : 1)) *
                         std::pow(2.0, optional);
    if (steps > kPatternStepBudget) {
      char text[160];
      std::snprintf(text, sizeof text, "may backtrack about %.3g steps on a subject of %zu bytes (at most %.3g allowed)",
                    steps, n, kPatternStepBudget);
      return luaL_error(L,
                        "%s: the pattern '%s' %s; use fewer repetitions (*, +, -, ?), anchor it with ^, or search "
                        "a shorter string",
                        lua_tostring(L, lua_upvalueindex(2)), pattern, text);
    }
  }
  return CallOriginal(L);
}

// The message handler a script gives xpcall, called through this guard. An
// error raised by a limit comes from inside a hook, where Lua runs no hooks:
// a handler run then would be unbounded, so it is skipped.
int GuardedHandler(lua_State* L) {
  if (LuaState::LimitPassed(L)) return 1;  // the message as it is
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, lua_gettop(L) - 1, 1);
  return 1;
}

int GuardedXpcall(lua_State* L) {
  luaL_checktype(L, 2, LUA_TFUNCTION);
  lua_pushvalue(L, 2);
  lua_pushcclosure(L, &GuardedHandler, 1);
  lua_replace(L, 2);
  return CallOriginal(L);
}

int GuardedSetMetatable(lua_State* L) {
  if (lua_type(L, 2) == LUA_TTABLE) {
    lua_pushliteral(L, "__gc");
    const bool finalizer = lua_rawget(L, 2) != LUA_TNIL;  // raw, as Lua itself looks
    lua_pop(L, 1);
    if (finalizer)
      return luaL_error(L,
                        "setmetatable: finalizers (__gc) are not allowed in mechflow's Lua: they run where no "
                        "limit can stop them; release resources explicitly instead");
  }
  return CallOriginal(L);
}

// Replaces table[name] by `guard` with upvalues (original, extra...).
void Wrap(lua_State* L, int table, const char* name, lua_CFunction guard, int extra_upvalues) {
  lua_getfield(L, table, name);
  lua_insert(L, -1 - extra_upvalues);  // the original goes below the extras
  lua_pushcclosure(L, guard, 1 + extra_upvalues);
  lua_setfield(L, table, name);
}

// Gives the metatable of the value on top of the stack __metatable = false
// (creating an empty metatable if it has none), then pops the value.
void Protect(lua_State* L) {
  if (!lua_getmetatable(L, -1)) {
    lua_newtable(L);
    lua_pushvalue(L, -1);
    lua_setmetatable(L, -3);
  }
  lua_pushboolean(L, 0);
  lua_setfield(L, -2, "__metatable");
  lua_pop(L, 2);
}

}  // namespace

void InstallLuaGuards(lua_State* L, std::size_t memory_limit) {
  lua_getglobal(L, LUA_STRLIBNAME);
  const int string = lua_gettop(L);
  Wrap(L, string, "rep", &GuardedRep, 0);
  for (const char* name : {"find", "match", "gmatch", "gsub"}) {
    lua_pushfstring(L, "string.%s", name);
    lua_pushboolean(L, std::strcmp(name, "find") == 0);
    Wrap(L, string, name, &GuardedPattern, 2);
  }
  lua_pop(L, 1);

  lua_getglobal(L, LUA_TABLIBNAME);
  // a table slot takes at least 16 bytes
  lua_pushinteger(L, static_cast<lua_Integer>(memory_limit / 16));
  Wrap(L, lua_gettop(L) - 1, "move", &GuardedMove, 1);
  lua_pop(L, 1);

  lua_pushglobaltable(L);
  Wrap(L, lua_gettop(L), "setmetatable", &GuardedSetMetatable, 0);
  Wrap(L, lua_gettop(L), "xpcall", &GuardedXpcall, 0);
  Protect(L);
  lua_pushliteral(L, "");
  Protect(L);
}

}  // namespace mechflow::scripting
