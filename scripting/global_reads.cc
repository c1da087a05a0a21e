#include "scripting/global_reads.h"

#include <algorithm>
#include <set>

#include <lua.hpp>

#include "scripting/identifiers.h"
#include "scripting/lua_lexer.h"
#include "scripting/lua_state.h"

namespace mechflow::scripting {
namespace {

struct Token {
  LuaToken kind;
  std::string text;
  int line;
};

// The chunk's tokens without spaces and comments, each with its line.
std::vector<Token> Tokens(const std::string& code) {
  std::vector<Token> tokens;
  int line = 1;
  for (std::size_t i = 0; i < code.size();) {
    std::size_t end = i;
    const LuaToken kind = NextLuaToken(code, i, &end);
    if (kind != LuaToken::kSpace && kind != LuaToken::kComment) tokens.push_back({kind, code.substr(i, end - i), line});
    line += static_cast<int>(std::count(code.begin() + i, code.begin() + end, '\n'));
    i = end;
  }
  return tokens;
}

bool IsKeyword(const std::string& name) { return !IsLuaName(name); }

}  // namespace

std::vector<GlobalRead> GlobalReads(const std::string& code) {
  const std::vector<Token> t = Tokens(code);
  const auto text = [&](std::size_t i) -> const std::string& {
    static const std::string none;
    return i < t.size() ? t[i].text : none;
  };
  const auto is_name = [&](std::size_t i) { return i < t.size() && t[i].kind == LuaToken::kName && !IsKeyword(t[i].text); };
  std::set<std::string> declared;
  std::vector<GlobalRead> reads;
  std::vector<char> brackets;  // open '{' '(' '['
  for (std::size_t i = 0; i < t.size(); ++i) {
    const std::string& s = t[i].text;
    if (t[i].kind == LuaToken::kPunctuation) {
      if (s == "{" || s == "(" || s == "[") brackets.push_back(s[0]);
      if ((s == "}" || s == ")" || s == "]") && !brackets.empty()) brackets.pop_back();
      continue;
    }
    if (t[i].kind != LuaToken::kName) continue;
    if (s == "local" || s == "for") {  // declared names up to '=' or 'in' (attributes <const> skipped)
      std::size_t j = i + 1;
      if (text(j) == "function") continue;  // 'local function f': the function rule declares f
      for (; j < t.size() && text(j) != "=" && text(j) != "in"; ++j)
        if (is_name(j) && text(j - 1) != "<") declared.insert(text(j));
      i = j - 1;
      continue;
    }
    if (s == "function") {  // name (a.b:c reads a), then the parameters
      std::size_t j = i + 1;
      if (is_name(j)) {
        if (text(j + 1) == "." || text(j + 1) == ":") reads.push_back({text(j), t[j].line});
        else declared.insert(text(j));
        while (j < t.size() && text(j) != "(") ++j;
      }
      for (++j; j < t.size() && text(j) != ")"; ++j)
        if (is_name(j)) declared.insert(text(j));
      i = j;
      continue;
    }
    if (s == "goto") {
      ++i;
      continue;
    }
    if (IsKeyword(s)) continue;
    const std::string& before = text(i - 1);
    if (i > 0 && (before == "." || before == ":" || before == "::")) continue;  // field, method, label
    if (text(i + 1) == "=" && text(i + 2) != "=") {
      const bool table_key = !brackets.empty() && brackets.back() == '{' && (before == "{" || before == "," || before == ";");
      if (!table_key) declared.insert(s);  // an assignment defines it
      continue;
    }
    reads.push_back({s, t[i].line});
  }
  std::vector<GlobalRead> out;
  std::set<std::string> seen;
  for (const GlobalRead& r : reads)
    if (!declared.count(r.name) && seen.insert(r.name).second) out.push_back(r);
  return out;
}

std::vector<GlobalRead> UnknownGlobals(const std::string& code, const IdentifierTable& identifiers,
                                       const LuaState& lua) {
  std::vector<GlobalRead> unknown;
  lua_State* L = lua.get();
  for (const GlobalRead& r : GlobalReads(code)) {
    if (identifiers.Has(r.name)) continue;
    lua_pushglobaltable(L);  // raw: a metatable on the globals must not run here
    lua_pushstring(L, r.name.c_str());
    lua_rawget(L, -2);
    const bool defined = !lua_isnil(L, -1);
    lua_pop(L, 2);
    if (!defined) unknown.push_back(r);
  }
  return unknown;
}

}  // namespace mechflow::scripting
