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

// Subjects this long make a guarded function look at the clock after its
// work (CheckTimeSoon): a loop of such calls would otherwise run on for
// LuaState::kCheckInterval of them past the time limit.
constexpr std::size_t kLongSubject = std::size_t(64) << 10;

// Calls the original function (upvalue 1) with this call's arguments.
int CallOriginal(lua_State* L) {
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, lua_gettop(L) - 1, LUA_MULTRET);
  return lua_gettop(L);
}

// Refuses the call: "<what>: <text>", raised as a limit's error.
int Refuse(lua_State* L, const char* what, const char* text) {
  // on the stack, and cut when long: Lua's error unwinds with longjmp, past
  // any destructor
  char message[400];
  if (std::snprintf(message, sizeof message, "%s: %s", what, text) < 0) return LuaState::RaiseLimit(L, what);
  return LuaState::RaiseLimit(L, message);
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

// "9.0072e+15 elements are more than a table can hold under the memory limit (1.67772e+07)"
int RefuseElements(lua_State* L, const char* what, double count, double most) {
  char text[200];
  std::snprintf(text, sizeof text, "%.6g elements are more than a table can hold under the memory limit (%.6g)", count,
                most);
  return Refuse(L, what, text);
}

// table.move(a1, f, e, t [, a2]); upvalue 2: the most elements allowed.
int GuardedMove(lua_State* L) {
  const lua_Integer f = luaL_checkinteger(L, 2);
  const lua_Integer e = luaL_checkinteger(L, 3);
  const double count = static_cast<double>(e) - static_cast<double>(f) + 1.0;
  const double most = static_cast<double>(lua_tointeger(L, lua_upvalueindex(2)));
  if (count > most) return RefuseElements(L, "table.move", count, most);
  return CallOriginal(L);
}

// The table functions that loop over a length: insert(t, pos, v) and
// remove(t, pos) shift the elements after pos, sort and concat visit all.
// Without __len the length is a border of what the table holds, which the
// memory limit bounds; a __len may claim any length, over which these would
// loop in C on nils. Upvalue 2: the most elements allowed; upvalue 3: the
// name; upvalue 4: the fewest arguments with which the call loops (insert
// with a position: 3, remove with one: 2, sort and concat: 1).
int GuardedLength(lua_State* L) {
  const char* what = lua_tostring(L, lua_upvalueindex(3));
  const double most = static_cast<double>(lua_tointeger(L, lua_upvalueindex(2)));
  const bool concat = std::strcmp(what, "table.concat") == 0;
  if (concat && !lua_isnoneornil(L, 4)) {  // an explicit range: no length needed
    const double count = static_cast<double>(luaL_checkinteger(L, 4)) -
                         static_cast<double>(luaL_optinteger(L, 3, 1)) + 1.0;
    if (count > most) return RefuseElements(L, what, count, most);
    return CallOriginal(L);
  }
  if (lua_gettop(L) >= lua_tointeger(L, lua_upvalueindex(4)) && luaL_getmetafield(L, 1, "__len") != LUA_TNIL) {
    lua_pop(L, 1);
    const double length = static_cast<double>(luaL_len(L, 1));  // the function runs once more here
    if (length > most) {
      char text[200];
      std::snprintf(text, sizeof text,
                    "the length %.6g (from the table's __len) is more than a table can hold under the memory limit "
                    "(%.6g elements)",
                    length, most);
      return Refuse(L, what, text);
    }
  }
  return CallOriginal(L);
}

// collectgarbage: a full collection takes time in proportion to the heap.
int GuardedCollect(lua_State* L) {
  const int results = CallOriginal(L);
  LuaState::CheckTimeSoon(L);
  return results;
}

// The repetition items (*, +, -) of a Lua pattern, sets and escapes skipped:
// each lets the matcher backtrack over the subject once more, and so do
// %bxy (it scans for its closing character) and back-references %1-%9
// (each compares a capture as long as the subject). Optional items (?) are
// counted in *optional: each doubles the ways to match.
int Repetitions(const char* p, std::size_t size, int* optional) {
  int count = 0;
  *optional = 0;
  for (std::size_t i = 0; i < size; ++i) {
    const char c = p[i];
    if (c == '%') {
      if (i + 1 < size && (p[i + 1] == 'b' || (p[i + 1] >= '1' && p[i + 1] <= '9'))) ++count;
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

// True when Lua's string.find searches `p` as plain text (lstrlib's nospecials).
bool NoSpecials(const char* p, std::size_t size) {
  for (std::size_t i = 0; i < size; ++i)
    if (std::strchr("^$*+?.([%-", p[i]) && p[i] != '\0') return false;
  return true;
}

// Lua's posrelatI: a 1-based start position, negative from the end, clipped to 1.
std::size_t StartPosition(lua_Integer pos, std::size_t length) {
  if (pos > 0) return static_cast<std::size_t>(pos);
  if (pos == 0 || pos < -static_cast<lua_Integer>(length)) return 1;
  return length + static_cast<std::size_t>(pos) + 1;
}

// A plain string.find in time linear in n + m (Knuth-Morris-Pratt; Lua's own
// search compares the needle at every position: n m steps). Same results:
// the first match at or after init, its start and end (1-based), or fail.
int LinearFind(lua_State* L, const char* s, std::size_t n, const char* p, std::size_t m) {
  const std::size_t init = StartPosition(luaL_optinteger(L, 3, 1), n) - 1;
  if (init > n || m > n - init) {
    luaL_pushfail(L);
    return 1;
  }
  if (m == 0) {
    lua_pushinteger(L, static_cast<lua_Integer>(init) + 1);
    lua_pushinteger(L, static_cast<lua_Integer>(init));
    return 2;
  }
  // border[i]: length of the longest proper border of p[0..i]
  auto* border = static_cast<std::size_t*>(lua_newuserdatauv(L, m * sizeof(std::size_t), 0));
  border[0] = 0;
  for (std::size_t i = 1, k = 0; i < m; ++i) {
    while (k > 0 && p[i] != p[k]) k = border[k - 1];
    if (p[i] == p[k]) ++k;
    border[i] = k;
  }
  for (std::size_t i = init, k = 0; i < n; ++i) {
    while (k > 0 && s[i] != p[k]) k = border[k - 1];
    if (s[i] == p[k] && ++k == m) {
      lua_pushinteger(L, static_cast<lua_Integer>(i + 2 - m));
      lua_pushinteger(L, static_cast<lua_Integer>(i + 1));
      return 2;
    }
  }
  luaL_pushfail(L);
  return 1;
}

enum PatternFunction { kFind, kMatch, kGmatch, kGsub };

// string.find/match/gmatch/gsub(s, pattern, ...); upvalue 2: the name,
// upvalue 3: which (PatternFunction).
int GuardedPattern(lua_State* L) {
  std::size_t n = 0, m = 0;
  const char* s = luaL_checklstring(L, 1, &n);
  const char* pattern = luaL_checklstring(L, 2, &m);
  const auto function = static_cast<PatternFunction>(lua_tointeger(L, lua_upvalueindex(3)));
  const double budget = kPatternStepBudget;
  if (function == kFind && (lua_toboolean(L, 4) || NoSpecials(pattern, m))) {
    // a plain search: Lua's takes up to n m steps
    if ((static_cast<double>(n) + 1.0) * static_cast<double>(m) > budget) return LinearFind(L, s, n, pattern, m);
  } else {
    int optional = 0;
    const int repetitions = Repetitions(pattern, m, &optional);
    const bool anchored = m > 0 && pattern[0] == '^' && function != kGmatch;  // gmatch reads ^ as a character
    // each start position tries every item; each repetition multiplies that by the subject's length
    const double steps = std::pow(static_cast<double>(n) + 1.0, repetitions + (anchored ? 0 : 1)) *
                         std::pow(2.0, optional) * static_cast<double>(m > 0 ? m : 1);
    if (steps > budget) {
      char text[300];
      std::snprintf(text, sizeof text,
                    "the pattern '%.60s%s' may take about %.3g steps on a subject of %zu bytes (at most %.3g "
                    "allowed); use a shorter pattern with fewer repetitions (*, +, -, ?, %%b, %%1), anchor it with "
                    "^, or search a shorter string",
                    pattern, m > 60 ? "..." : "", steps, n, budget);
      return Refuse(L, lua_tostring(L, lua_upvalueindex(2)), text);
    }
  }
  const int results = CallOriginal(L);
  if (n >= kLongSubject) LuaState::CheckTimeSoon(L);
  return results;
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
      return Refuse(L, "setmetatable",
                    "finalizers (__gc) are not allowed in mechflow's Lua: they run where no limit can stop them; "
                    "release resources explicitly instead");
  }
  return CallOriginal(L);
}

// load(chunk, ...): a chunk read by a function is read whole first, so that
// its compile cost can be judged like a text's (Lua reads such a chunk piece
// by piece while it compiles; an error of the reader is load's failure, as
// in Lua). The chunk name of such a chunk stays Lua's "=(load)".
int GuardedLoad(lua_State* L) {
  if (lua_type(L, 1) == LUA_TFUNCTION) {
    luaL_Buffer pieces;
    luaL_buffinit(L, &pieces);
    for (;;) {
      lua_pushvalue(L, 1);
      if (lua_pcall(L, 0, 1, 0) != LUA_OK) {
        luaL_pushfail(L);
        lua_insert(L, -2);
        return 2;  // fail, the message
      }
      if (lua_isnil(L, -1) || (lua_type(L, -1) == LUA_TSTRING && lua_rawlen(L, -1) == 0)) {
        lua_pop(L, 1);
        break;
      }
      if (lua_type(L, -1) != LUA_TSTRING) {
        luaL_pushfail(L);
        lua_pushliteral(L, "reader function must return a string");
        return 2;
      }
      luaL_addvalue(&pieces);
    }
    luaL_pushresult(&pieces);
    lua_replace(L, 1);
    if (lua_gettop(L) < 2) lua_settop(L, 2);
    if (lua_isnil(L, 2)) {
      lua_pushliteral(L, "=(load)");
      lua_replace(L, 2);
    }
  }
  if (lua_type(L, 1) == LUA_TSTRING) {
    std::size_t size = 0;
    const char* code = lua_tolstring(L, 1, &size);
    char text[400];
    if (DescribeCompileCost(code, size, text, sizeof text)) return Refuse(L, "load", text);
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

bool IsNameByte(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
}

}  // namespace

bool DescribeCompileCost(const char* code, std::size_t size, char* text, std::size_t text_size) {
  // whole words anywhere (in strings and comments too: an overcount is safe)
  double and_or = 0, elseif = 0, jumps = 0;
  for (std::size_t i = 0; i < size;) {
    if (code[i] == ':' && i + 1 < size && code[i + 1] == ':') {
      jumps += 0.5;  // a label has two
      i += 2;
      continue;
    }
    if (!IsNameByte(code[i])) {
      ++i;
      continue;
    }
    std::size_t end = i;
    while (end < size && IsNameByte(code[end])) ++end;
    const std::size_t length = end - i;
    const auto is = [&](const char* word) { return length == std::strlen(word) && std::memcmp(code + i, word, length) == 0; };
    if (is("and") || is("or")) and_or += 1;
    else if (is("elseif")) elseif += 1;
    else if (is("goto") || is("break")) jumps += 1;
    i = end;
  }
  const double steps = (and_or * and_or + elseif * elseif + jumps * jumps) / 2;
  if (steps <= kCompileStepBudget) return false;
  std::snprintf(text, text_size,
                "the chunk has %.0f 'and'/'or', %.0f 'elseif' and %.0f goto, break and labels; Lua's compiler takes "
                "time growing with the square of each count (about %.3g steps, at most %.3g allowed); write fewer "
                "of them in one chunk",
                and_or, elseif, std::floor(jumps), steps, kCompileStepBudget);
  return true;
}

std::string CompileCostProblem(std::string_view code) {
  char text[400];
  return DescribeCompileCost(code.data(), code.size(), text, sizeof text) ? std::string(text) : std::string();
}

void InstallLuaGuards(lua_State* L, std::size_t memory_limit) {
  lua_getglobal(L, LUA_STRLIBNAME);
  const int string = lua_gettop(L);
  Wrap(L, string, "rep", &GuardedRep, 0);
  const struct {
    const char* name;
    PatternFunction function;
  } kPatterns[] = {{"find", kFind}, {"match", kMatch}, {"gmatch", kGmatch}, {"gsub", kGsub}};
  for (const auto& p : kPatterns) {
    lua_pushfstring(L, "string.%s", p.name);
    lua_pushinteger(L, p.function);
    Wrap(L, string, p.name, &GuardedPattern, 2);
  }
  lua_pop(L, 1);

  lua_getglobal(L, LUA_TABLIBNAME);
  const int table = lua_gettop(L);
  // a table slot takes at least 16 bytes
  const auto most = static_cast<lua_Integer>(memory_limit / 16);
  lua_pushinteger(L, most);
  Wrap(L, table, "move", &GuardedMove, 1);
  const struct {
    const char* name;
    int looping_arguments;
  } kLengths[] = {{"insert", 3}, {"remove", 2}, {"sort", 1}, {"concat", 1}};
  for (const auto& f : kLengths) {
    lua_pushinteger(L, most);
    lua_pushfstring(L, "table.%s", f.name);
    lua_pushinteger(L, f.looping_arguments);
    Wrap(L, table, f.name, &GuardedLength, 3);
  }
  lua_pop(L, 1);

  lua_pushglobaltable(L);
  const int globals = lua_gettop(L);
  Wrap(L, globals, "setmetatable", &GuardedSetMetatable, 0);
  Wrap(L, globals, "xpcall", &GuardedXpcall, 0);
  Wrap(L, globals, "collectgarbage", &GuardedCollect, 0);
  Wrap(L, globals, "load", &GuardedLoad, 0);
  Protect(L);
  lua_pushliteral(L, "");
  Protect(L);
}

}  // namespace mechflow::scripting
