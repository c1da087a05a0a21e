#include "scripting/identifiers.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <unordered_set>

#include <lua.hpp>

#include "blocks/support/excerpt.h"
#include "blocks/support/message_number.h"
#include "blocks/support/suggest.h"
#include "mech/errors.h"
#include "scripting/instance_path.h"
#include "scripting/lua_guards.h"
#include "scripting/lua_state.h"

namespace mechflow::scripting {
namespace {

constexpr const char* kKeywords[] = {"and",    "break", "do",    "else", "elseif", "end",   "false", "for",
                                     "function", "goto", "if",  "in",   "local",  "nil",   "not",   "or",
                                     "repeat", "return", "then", "true", "until",  "while"};
// names that mean something else inside expressions
constexpr const char* kArgumentNames[] = {"t", "x", "v"};
// the Lua globals an expression may need (lower-case, as identifiers are stored)
constexpr const char* kLuaGlobals[] = {
    "assert", "collectgarbage", "dofile", "error", "getmetatable", "ipairs", "load",   "loadfile", "next",
    "pairs",  "pcall",          "print",  "rawequal", "rawget",    "rawlen", "rawset", "require",  "select",
    "setmetatable", "tonumber", "tostring", "type", "xpcall", "warn", "_g", "_version", "_env", "math",
    "string", "table", "utf8", "io", "os", "debug", "package", "coroutine"};

// Chunk name of load-time expressions; Lua's "expression:1: " is cut from
// messages, which already say which identifier or parameter failed.
constexpr char kChunkName[] = "=expression";
constexpr char kChunkLabel[] = "expression:";

template <std::size_t N>
bool Contains(const char* const (&list)[N], const std::string& name) {
  return std::find_if(std::begin(list), std::end(list), [&](const char* s) { return name == s; }) != std::end(list);
}

std::string Trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(" \t\r\n") - first + 1);
}

// "expression:1: unexpected symbol" -> "unexpected symbol"
std::string WithoutPosition(std::string message) {
  if (message.rfind(kChunkLabel, 0) != 0) return message;
  std::size_t i = sizeof(kChunkLabel) - 1;
  while (i < message.size() && std::isdigit(static_cast<unsigned char>(message[i]))) ++i;
  if (i + 1 < message.size() && message[i] == ':' && message[i + 1] == ' ') message.erase(0, i + 2);
  return message;
}

// --- Lua side of the evaluation environment ------------------------------------
// Called by Lua: no C++ objects with destructors (lua_error long-jumps).

// What an expression's environment sees: the first `visible` identifiers of
// `table`. A full userdata the environment holds; Eval clears `table` when
// the evaluation ends, so a function the expression leaked (into a global,
// say) fails instead of reading a table that may be gone.
struct VisibleIdentifiers {
  const IdentifierTable* table;
  int visible;
};

// __index of the environment: the visible identifier with the lower-cased
// name (a hash lookup, so an expression costs the same over 10 or 10^5
// identifiers), else the global of that exact name, else an error object
// {unknown = name}.
int LowerCaseIndex(lua_State* L) {
  if (lua_type(L, 2) != LUA_TSTRING) return 0;
  const auto* visible = static_cast<const VisibleIdentifiers*>(lua_touserdata(L, lua_upvalueindex(1)));
  if (!visible->table) return luaL_error(L, "an expression's names are read after its evaluation ended");
  std::size_t length = 0;
  const char* key = lua_tolstring(L, 2, &length);
  luaL_Buffer buffer;
  char* lower = luaL_buffinitsize(L, &buffer, length);
  for (std::size_t i = 0; i < length; ++i) lower[i] = static_cast<char>(std::tolower(static_cast<unsigned char>(key[i])));
  const int id = visible->table->FindLowerCase(std::string_view(lower, length));
  if (id >= 0 && id < visible->visible) {
    lua_pushnumber(L, visible->table->value(id));
    return 1;
  }
  if (lua_getglobal(L, key) != LUA_TNIL) return 1;
  lua_createtable(L, 0, 1);
  lua_pushvalue(L, 2);
  lua_setfield(L, -2, "unknown");
  return lua_error(L);
}

// Returns a new environment table for the identifiers [0, visible) of the
// table passed as a light userdata, and the VisibleIdentifiers it holds.
// Run in protected mode: it allocates. Its cost does not depend on how many
// identifiers there are.
int BuildEnvironment(lua_State* L) {
  const auto* table = static_cast<const IdentifierTable*>(lua_touserdata(L, 1));
  const int visible = static_cast<int>(lua_tointeger(L, 2));
  lua_createtable(L, 0, 0);  // the environment, empty: every lookup goes to __index
  lua_createtable(L, 0, 1);  // its metatable
  auto* seen = static_cast<VisibleIdentifiers*>(lua_newuserdatauv(L, sizeof(VisibleIdentifiers), 0));
  *seen = {table, visible};
  lua_pushvalue(L, -1);
  lua_insert(L, -4);  // environment, metatable, userdata -> userdata, environment, metatable, userdata
  lua_pushcclosure(L, &LowerCaseIndex, 1);
  lua_setfield(L, -2, "__index");
  lua_setmetatable(L, -2);
  lua_insert(L, -2);  // -> environment, userdata
  return 2;
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
  double parsed = 0.0;
  const auto [end, error] = std::from_chars(begin, t.data() + t.size(), parsed);
  if (error != std::errc() || end != t.data() + t.size() || !std::isfinite(parsed)) return false;
  *value = parsed;
  return true;
}

bool IsLuaName(const std::string& s) {
  if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
  if (!std::all_of(s.begin(), s.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }))
    return false;
  return !Contains(kKeywords, s);
}

void IdentifierTable::Add(const std::string& name, const std::string& definition, const std::string& origin,
                          const std::string& comment, const std::string& unit, double to_si) {
  // a path ("d[1].c", an instance's parameter) is known to Lua by its Lua name
  const bool path = IsInstancePath(name);
  if (path) {
    if (const std::string problem = InstancePathProblem(name); !problem.empty())
      throw InputError(origin + ": identifier name '" + name + "': " + problem);
  }
  const std::string lower = ToLower(path ? InstancePathLuaName(name) : name);
  const std::string last = path ? ToLower(name.substr(name.find_last_of(".]") + 1)) : lower;
  const bool keyword = Contains(kKeywords, last);
  if (!keyword && !path && !IsLuaName(name))
    throw InputError(origin + ": identifier name '" + name +
                     "' must start with a letter or '_' and contain only letters, digits and '_'");
  if (!path && name.find("__") != std::string::npos)
    throw InputError(origin + ": identifier name '" + name +
                     "' contains \"__\", which is kept for the parameters of subsystem and part instances");
  const char* why = keyword                          ? "a Lua keyword"
                    : Contains(kArgumentNames, last) ? "t is time, x and v are force-law arguments"
                    : LuaState::IsBuiltinName(last)  ? "a built-in function or constant"
                    : Contains(kLuaGlobals, last)    ? "a Lua function or library"
                                                      : nullptr;
  if (why) throw InputError(origin + ": identifier name '" + name + "' is reserved (" + why + "); choose another name");
  const int existing = Find(lower);
  if (existing >= 0)
    throw InputError(origin + ": identifier '" + name + "' is defined twice (first at " + items_[existing].origin +
                     "; names are case-insensitive)");
  Item item;
  item.name = lower;
  item.spelling = name;
  item.definition = Trim(definition);
  item.origin = origin;
  item.comment = comment;
  item.unit = unit;
  item.to_si = to_si;
  if (item.definition.empty()) throw InputError(origin + ": identifier '" + name + "' has an empty value");
  item.is_expression = !ParseNumber(item.definition, &item.value);
  if (!item.is_expression) {
    item.value *= to_si;
    if (!std::isfinite(item.value))
      throw InputError(origin + ": identifier '" + name + "': " + item.definition + " " + unit +
                       " is beyond the range of double precision in SI");
  }
  index_.emplace(lower, size());
  items_.push_back(std::move(item));
}

void IdentifierTable::Override(const std::string& name, double value) {
  const int i = Find(name);
  if (i < 0)
    throw InputError("no identifier named '" + name + "'" + blocks::DidYouMean(ToLower(name), ShownNames()) +
                     (items_.empty() ? "; the diagram defines none" : "; identifiers: " + blocks::JoinNames(ShownNames())));
  Item& item = items_[i];
  if (item.is_expression)
    throw InputError("identifier '" + Shown(item) + "' is defined by an expression (" + Shown(item) + " = " +
                     WithInstancePaths(item.definition) + ", at " + item.origin + "); set the identifiers it depends on instead");
  if (!std::isfinite(value))
    throw InputError("identifier '" + Shown(item) + "' cannot be set to " + std::to_string(value) +
                     "; expected a finite number");
  item.value = value;
  item.overridden = true;
}

double IdentifierTable::Eval(LuaState& lua, const std::string& text, int visible, int self,
                             const std::string& what) const {
  lua_State* L = lua.get();
  const int top = lua_gettop(L);

  // compile: "return <text>" accepts exactly an expression list; Lua's
  // compiler is quadratic in some constructs, so a text it would spend
  // minutes on is refused first
  if (const std::string problem = CompileCostProblem(text); !problem.empty())
    throw InputError(what + ": " + problem);
  const std::string chunk = "return " + text;
  int status = luaL_loadbufferx(L, chunk.data(), chunk.size(), kChunkName, "t");
  if (status != LUA_OK) {
    const std::string message = WithoutPosition(lua.ErrorText(status));
    lua_settop(L, top);
    throw InputError(what + ": '" + blocks::Excerpt(text) + "' is not a valid expression: " + message);
  }

  // environment: the visible identifiers (case-insensitive), then the globals
  lua_pushcfunction(L, &BuildEnvironment);
  lua_pushlightuserdata(L, const_cast<IdentifierTable*>(this));
  lua_pushinteger(L, visible);
  status = lua_pcall(L, 2, 2, 0);
  if (status != LUA_OK) {
    const std::string message = lua.ErrorText(status);
    lua_settop(L, top);
    throw InputError(what + ": " + message);
  }
  // stack: chunk, environment, its VisibleIdentifiers -> VisibleIdentifiers, chunk (which holds the environment)
  auto* seen = static_cast<VisibleIdentifiers*>(lua_touserdata(L, -1));
  lua_insert(L, top + 1);
  lua_setupvalue(L, top + 2, 1);  // the chunk's only upvalue is _ENV
  const int base = top + 1;       // results come above the VisibleIdentifiers, kept alive until they are read

  // run, bounded
  {
    BoundedCall bounded(lua);
    status = lua_pcall(L, 0, LUA_MULTRET, 0);
  }
  seen->table = nullptr;
  if (status != LUA_OK) {
    std::string unknown;
    if (lua_istable(L, -1) && lua_getfield(L, -1, "unknown") == LUA_TSTRING) unknown = lua_tostring(L, -1);
    const std::string message = unknown.empty() ? WithoutPosition(lua.ErrorText(status)) : "";
    lua_settop(L, top);
    if (message.empty()) {
      const int defined = Find(unknown);
      if (defined >= 0 && defined == self)
        throw InputError(what + ": uses itself; an identifier may only use identifiers above it");
      if (defined >= visible)
        throw InputError(what + ": uses '" + unknown + "', which is defined below it (at " + items_[defined].origin +
                         "); an identifier may only use identifiers above it");
      std::vector<std::string> candidates = LuaState::BuiltinNames();
      for (int i = 0; i < visible; ++i) candidates.push_back(items_[i].name);
      // a one-letter name is close to too many others for a suggestion to help
      std::string hint = unknown.size() > 1 ? blocks::DidYouMean(unknown, candidates) : "";
      if (Contains(kArgumentNames, ToLower(unknown)))
        hint = " (t, x and v have values only while the model runs; identifiers and parameters are evaluated "
               "once, when the diagram is loaded)";
      throw InputError(what + ": unknown name '" + unknown + "'" + hint);
    }
    throw InputError(what + ": error evaluating '" + blocks::Excerpt(text) + "': " + message);
  }

  // exactly one finite number
  const int results = lua_gettop(L) - base;
  const int type = results > 0 ? lua_type(L, base + 1) : LUA_TNIL;
  const double value = type == LUA_TNUMBER ? lua_tonumber(L, base + 1) : 0.0;
  lua_settop(L, top);
  if (results != 1)
    throw InputError(what + ": '" + blocks::Excerpt(text) + "' gives " + std::to_string(results) +
                     " values; expected one number");
  if (type != LUA_TNUMBER)
    throw InputError(what + ": '" + blocks::Excerpt(text) + "' does not give a number (it gives a " +
                     lua_typename(L, type) + ")" +
                     (type == LUA_TBOOLEAN ? "; write 'cond and 1 or 0' for a number" : ""));
  if (!std::isfinite(value))
    throw InputError(what + ": '" + blocks::Excerpt(text) + "' gives " + std::to_string(value) +
                     ValuesNamedIn(text, visible));
  return value;
}

std::string IdentifierTable::ValuesNamedIn(const std::string& text, int visible) const {
  const auto name_char = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
  std::string out;
  std::unordered_set<int> named;
  for (std::size_t k = 0; k < text.size();) {
    if (!name_char(text[k])) {
      ++k;
      continue;
    }
    std::size_t end = k;
    while (end < text.size() && name_char(text[end])) ++end;
    const std::string token = text.substr(k, end - k);
    k = end;
    if (std::isdigit(static_cast<unsigned char>(token[0]))) continue;  // a number (1e3 too)
    const int i = Find(token);
    if (i >= 0 && i < visible && named.insert(i).second)
      out += (out.empty() ? " (with " : ", ") + Shown(items_[i]) + " = " + blocks::MessageNumber(items_[i].value);
  }
  return out.empty() ? "" : out + " in SI)";
}

void IdentifierTable::Evaluate(LuaState& lua) {
  for (int i = 0; i < size(); ++i) {
    Item& item = items_[i];
    if (!item.is_expression) continue;
    item.value = Eval(lua, item.definition, i, i, item.origin + ": identifier '" + Shown(item) + "'");
  }
}

double IdentifierTable::EvaluateExpression(LuaState& lua, const std::string& text, const std::string& what) const {
  const double value = Eval(lua, text, size(), -1, what);
  NoteFixedUses(text, what);
  return value;
}

void IdentifierTable::NoteFixedUses(const std::string& text, const std::string& what) const {
  // repeats are removed when the uses are read (rarely): a search here would
  // cost every block that uses an identifier all the places noted before
  for (const int id : NamedIn(text)) {
    auto& uses = items_[id].fixed_uses;
    if (uses.empty() || uses.back() != what) uses.push_back(what);
  }
}

const std::vector<std::string>& IdentifierTable::fixed_uses(int i) const {
  const Item& item = items_.at(i);
  auto& uses = item.fixed_uses;
  if (item.unique_uses == uses.size()) return uses;
  std::unordered_set<std::string> seen;
  std::vector<std::string> unique;
  for (const std::string& use : uses)
    if (seen.insert(use).second) unique.push_back(use);
  uses = std::move(unique);
  item.unique_uses = uses.size();
  return uses;
}

std::vector<int> IdentifierTable::NamedIn(const std::string& text) const {
  std::vector<int> named;
  for (std::size_t i = 0; i < text.size();) {
    const unsigned char c = text[i];
    if (!std::isalpha(c) && c != '_') {
      i += std::isdigit(c) ? std::strspn(text.c_str() + i, "0123456789.eE") : 1;
      continue;
    }
    const std::size_t end = text.find_first_not_of(
        "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_", i);
    const std::size_t stop = end == std::string::npos ? text.size() : end;
    const bool field = i > 0 && (text[i - 1] == '.' || text[i - 1] == ':');
    if (const int id = field ? -1 : Find(text.substr(i, stop - i)); id >= 0)
      if (std::find(named.begin(), named.end(), id) == named.end()) named.push_back(id);
    i = stop;
  }
  return named;
}

std::vector<double> IdentifierTable::Values() const {
  std::vector<double> values;
  for (const auto& item : items_) values.push_back(item.value);
  return values;
}

void IdentifierTable::SetValues(const std::vector<double>& values) {
  for (int i = 0; i < size(); ++i) items_[i].value = values.at(i);
}

int IdentifierTable::Find(const std::string& name) const {
  return FindLowerCase(ToLower(IsInstancePath(name) ? InstancePathLuaName(name) : name));
}

int IdentifierTable::FindLowerCase(std::string_view lower) const noexcept {
  const auto it = index_.find(lower);
  return it == index_.end() ? -1 : it->second;
}

double IdentifierTable::Value(const std::string& name) const {
  const int i = Find(name);
  if (i < 0) throw std::out_of_range("no identifier '" + name + "'");
  return items_[i].value;
}

std::vector<std::string> IdentifierTable::ShownNames() const {
  std::vector<std::string> names;
  for (const auto& item : items_) names.push_back(Shown(item));
  return names;
}

std::vector<std::string> IdentifierTable::Names() const {
  std::vector<std::string> names;
  for (const auto& item : items_) names.push_back(item.name);
  return names;
}

}  // namespace mechflow::scripting
