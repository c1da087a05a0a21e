#include "scripting/identifier_bindings.h"

#include <algorithm>
#include <string_view>
#include <unordered_set>

#include <lua.hpp>

#include "scripting/identifiers.h"
#include "scripting/lua_lexer.h"

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

IdentifierChunk IdentifiersAsUpvalues(const std::string& code, const IdentifierTable& identifiers) {
  IdentifierChunk out;
  std::string body;
  body.reserve(code.size());
  std::string previous;           // the previous token that is not space or comment
  std::vector<char> brackets;     // open '{' '(' '['
  for (std::size_t i = 0, end = 0; i < code.size(); i = end) {
    const LuaToken kind = NextLuaToken(code, i, &end);
    std::string token = code.substr(i, end - i);
    if (kind == LuaToken::kSpace || kind == LuaToken::kComment) {
      body += token;
      continue;
    }
    if (kind == LuaToken::kPunctuation) {
      if (token == "{" || token == "(" || token == "[") brackets.push_back(token[0]);
      if ((token == "}" || token == ")" || token == "]") && !brackets.empty()) brackets.pop_back();
    } else if (kind == LuaToken::kName && IsLuaName(token) && identifiers.Has(token)) {
      // not a field, method, label or goto target, nor a key of a table constructor
      std::size_t next = end, after = end;
      while (next < code.size()) {
        const LuaToken k = NextLuaToken(code, next, &after);
        if (k != LuaToken::kSpace && k != LuaToken::kComment) break;
        next = after;
      }
      const bool equals_follows = next < code.size() && code[next] == '=' && code.compare(next, 2, "==") != 0;
      const bool table_key = equals_follows && !brackets.empty() && brackets.back() == '{' &&
                             (previous == "{" || previous == "," || previous == ";");
      const bool field = previous == "." || previous == ":" || previous == "::" || previous == "goto";
      if (!field && !table_key) {
        token = ToLower(token);
        if (std::find(out.identifiers.begin(), out.identifiers.end(), token) == out.identifiers.end())
          out.identifiers.push_back(token);
      }
    }
    previous = code.substr(i, end - i);
    body += token;
  }
  out.code = "local __mechflow_binder";
  for (const std::string& name : out.identifiers) out.code += ", " + name + " <const>";
  out.code += " = ...; ";
  if (!out.identifiers.empty()) {
    out.code += "__mechflow_binder[1] = function() return ";
    for (std::size_t i = 0; i < out.identifiers.size(); ++i) out.code += (i ? ", " : "") + out.identifiers[i];
    out.code += " end; ";
  }
  out.code += "__mechflow_binder = nil; " + body;
  return out;
}

}  // namespace mechflow::scripting
