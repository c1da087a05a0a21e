#include "scripting/identifiers.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <stdexcept>

#include <lua.hpp>

#include "blocks/suggest.h"
#include "mech/errors.h"
#include "scripting/lua_state.h"

namespace mechflow::scripting {
namespace {

const char* const kKeywords[] = {"and",  "break", "do",   "else", "elseif", "end",   "false", "for",
                                 "function", "goto", "if", "in", "local", "nil", "not", "or",
                                 "repeat", "return", "then", "true", "until", "while"};
// names that mean something else inside expressions
const char* const kReserved[] = {"t", "x", "v"};

// Load-time expressions get this many VM instructions before they are stopped.
constexpr long kInstructionLimit = 10'000'000;

std::string Trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(" \t\r\n") - first + 1);
}

bool IsLuaName(const std::string& s) {
  if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
  return std::all_of(s.begin(), s.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
}

}  // namespace

std::string ToLower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

bool ParseNumber(const std::string& text, double* value) {
  const std::string t = Trim(text);
  if (t.empty()) return false;
  const char* begin = t.data();
  if (*begin == '+') ++begin;  // from_chars takes no leading plus
  const auto [end, error] = std::from_chars(begin, t.data() + t.size(), *value);
  return error == std::errc() && end == t.data() + t.size();
}

void IdentifierTable::Add(const std::string& name, const std::string& definition, const std::string& origin,
                          const std::string& comment, const std::string& unit) {
  const std::string lower = ToLower(name);
  if (!IsLuaName(name))
    throw InputError(origin + ": identifier name '" + name +
                     "' must start with a letter or '_' and contain only letters, digits and '_'");
  const bool keyword = std::find(std::begin(kKeywords), std::end(kKeywords), lower) != std::end(kKeywords);
  const bool reserved = std::find(std::begin(kReserved), std::end(kReserved), lower) != std::end(kReserved);
  if (keyword || reserved || LuaState::IsBuiltinName(lower))
    throw InputError(origin + ": identifier name '" + name + "' is reserved (" +
                     (keyword ? "a Lua keyword" : reserved ? "t is time, x and v are force-law arguments"
                                                           : "a built-in function or constant") +
                     "); choose another name");
  const int existing = Find(lower);
  if (existing >= 0)
    throw InputError(origin + ": identifier '" + name + "' is defined twice (first at " + items_[existing].origin +
                     "; names are case-insensitive)");
  Item item;
  item.name = lower;
  item.definition = Trim(definition);
  item.origin = origin;
  item.comment = comment;
  item.unit = unit;
  item.is_expression = !ParseNumber(item.definition, &item.value);
  if (item.definition.empty()) throw InputError(origin + ": identifier '" + name + "' has an empty value");
  items_.push_back(std::move(item));
}

void IdentifierTable::Override(const std::string& name, double value) {
  const int i = Find(name);
  if (i < 0)
    throw InputError("no identifier named '" + name + "'" + blocks::DidYouMean(ToLower(name), Names()) +
                     (items_.empty() ? "; the diagram defines none" : "; identifiers: " + blocks::JoinNames(Names())));
  Item& item = items_[i];
  if (item.is_expression)
    throw InputError("identifier '" + item.name + "' is defined by an expression (" + item.name + " = " +
                     item.definition + ", at " + item.origin + "); set the identifiers it depends on instead");
  item.value = value;
  item.overridden = true;
}

double IdentifierTable::Eval(LuaState& lua, const std::string& text, int visible, const std::string& what) const {
  lua_State* L = lua.get();
  const int top = lua_gettop(L);
  const std::string chunk = "return (" + text + "\n)";
  if (luaL_loadbufferx(L, chunk.data(), chunk.size(), "=expression", "t") != LUA_OK) {
    std::string message = lua_tostring(L, -1);
    lua_settop(L, top);
    throw InputError(what + ": '" + text + "' is not a valid expression: " + message);
  }
  // environment: visible identifiers (case-insensitive), then the globals;
  // an unknown name raises a table {unknown = name} recognised below
  lua_newtable(L);  // env
  lua_newtable(L);  // its metatable
  lua_newtable(L);  // values by lower-case name
  for (int i = 0; i < visible; ++i) {
    lua_pushnumber(L, items_[i].value);
    lua_setfield(L, -2, items_[i].name.c_str());
  }
  lua_pushcclosure(
      L,
      [](lua_State* S) -> int {
        // no C++ objects with destructors here: lua_error long-jumps
        const char* key = luaL_checkstring(S, 2);
        lua_pushstring(S, key);
        lua_getglobal(S, "string");
        lua_getfield(S, -1, "lower");
        lua_pushvalue(S, -3);
        lua_call(S, 1, 1);
        lua_gettable(S, lua_upvalueindex(1));
        if (!lua_isnil(S, -1)) return 1;
        lua_getglobal(S, key);
        if (!lua_isnil(S, -1)) return 1;
        lua_newtable(S);
        lua_pushstring(S, key);
        lua_setfield(S, -2, "unknown");
        return lua_error(S);
      },
      1);
  lua_setfield(L, -2, "__index");
  lua_setmetatable(L, -2);
  lua_setupvalue(L, -2, 1);  // the chunk's _ENV
  InstructionLimit limit(lua, kInstructionLimit);
  if (lua_pcall(L, 0, 1, 0) != LUA_OK) {
    std::string message;
    if (lua_istable(L, -1)) {
      lua_getfield(L, -1, "unknown");
      const std::string unknown = lua_tostring(L, -1);
      lua_settop(L, top);
      const int defined = Find(unknown);
      if (defined >= visible)
        throw InputError(what + ": uses '" + unknown + "', which is defined below it (at " + items_[defined].origin +
                         "); an identifier may only use identifiers above it");
      std::vector<std::string> names;
      for (int i = 0; i < visible; ++i) names.push_back(items_[i].name);
      throw InputError(what + ": unknown name '" + unknown + "'" + blocks::DidYouMean(ToLower(unknown), names));
    }
    message = lua_isstring(L, -1) ? lua_tostring(L, -1) : "error";
    lua_settop(L, top);
    throw InputError(what + ": error evaluating '" + text + "': " + message);
  }
  int is_number = 0;
  const double value = lua_tonumberx(L, -1, &is_number);
  lua_settop(L, top);
  if (!is_number) throw InputError(what + ": '" + text + "' does not give a number");
  if (!std::isfinite(value)) throw InputError(what + ": '" + text + "' gives " + std::to_string(value));
  return value;
}

void IdentifierTable::Evaluate(LuaState& lua) {
  for (int i = 0; i < size(); ++i) {
    Item& item = items_[i];
    if (!item.is_expression) continue;
    item.value = Eval(lua, item.definition, i, item.origin + ": identifier '" + item.name + "'");
  }
}

double IdentifierTable::EvaluateExpression(LuaState& lua, const std::string& text, const std::string& what) const {
  return Eval(lua, text, size(), what);
}

int IdentifierTable::Find(const std::string& name) const {
  const std::string lower = ToLower(name);
  for (int i = 0; i < size(); ++i)
    if (items_[i].name == lower) return i;
  return -1;
}

double IdentifierTable::Value(const std::string& name) const {
  const int i = Find(name);
  if (i < 0) throw std::out_of_range("no identifier '" + name + "'");
  return items_[i].value;
}

std::vector<std::string> IdentifierTable::Names() const {
  std::vector<std::string> names;
  for (const auto& item : items_) names.push_back(item.name);
  return names;
}

}  // namespace mechflow::scripting
