#include "scripting/compiled_expression.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>

#include <lua.hpp>

#include "mech/errors.h"
#include "scripting/identifiers.h"
#include "scripting/lua_state.h"

namespace mechflow::scripting {
namespace {

bool IsNameStart(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool IsNameChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

// Rewrites identifier names to lower case and collects the free names that
// need an upvalue (identifiers and built-ins). Strings and field names
// (after '.' or ':') are left alone.
std::string Rewrite(const std::string& expr, const std::vector<std::string>& arguments, const IdentifierTable& ids,
                    std::set<std::string>* used_identifiers, std::set<std::string>* used_builtins) {
  std::string out;
  size_t i = 0;
  char previous = 0;  // last non-space character copied
  while (i < expr.size()) {
    const char c = expr[i];
    if (c == '"' || c == '\'') {  // string literal
      size_t j = i + 1;
      while (j < expr.size() && expr[j] != c) j += expr[j] == '\\' ? 2 : 1;
      out.append(expr, i, j + 1 - i);
      i = j + 1;
      previous = c;
    } else if (std::isdigit(static_cast<unsigned char>(c)) ||
               (c == '.' && i + 1 < expr.size() && std::isdigit(static_cast<unsigned char>(expr[i + 1])))) {
      size_t j = i;
      while (j < expr.size() && (IsNameChar(expr[j]) || expr[j] == '.' ||
                                 ((expr[j] == '+' || expr[j] == '-') && j > i &&
                                  std::string("eEpP").find(expr[j - 1]) != std::string::npos)))
        ++j;
      out.append(expr, i, j - i);
      i = j;
      previous = '0';
    } else if (IsNameStart(c)) {
      size_t j = i;
      while (j < expr.size() && IsNameChar(expr[j])) ++j;
      std::string name = expr.substr(i, j - i);
      const bool field = previous == '.' || previous == ':';
      const bool argument = std::find(arguments.begin(), arguments.end(), name) != arguments.end();
      if (!field && !argument) {
        if (ids.Has(name)) {
          name = ToLower(name);
          used_identifiers->insert(name);
        } else if (LuaState::IsBuiltinName(name)) {
          used_builtins->insert(name);
        }
      }
      out += name;
      i = j;
      previous = 'a';
    } else {
      out += c;
      if (!std::isspace(static_cast<unsigned char>(c))) previous = c;
      ++i;
    }
  }
  return out;
}

}  // namespace

CompiledExpression::CompiledExpression(LuaState& lua, const std::string& expression,
                                       std::vector<std::string> argument_names, const IdentifierTable& identifiers,
                                       const std::string& chunk_name)
    : lua_(lua),
      expression_(expression),
      label_(chunk_name.size() > 1 && (chunk_name[0] == '=' || chunk_name[0] == '@') ? chunk_name.substr(1)
                                                                                       : chunk_name),
      arguments_(std::move(argument_names)) {
  std::set<std::string> used_identifiers, used_builtins;
  const std::string body = Rewrite(expression, arguments_, identifiers, &used_identifiers, &used_builtins);

  // the expression stays on line 1 of the chunk so Lua's line numbers match it
  std::string upvalues, arguments;
  for (const auto& name : used_builtins) upvalues += (upvalues.empty() ? "" : ", ") + name;
  for (const auto& name : used_identifiers) upvalues += (upvalues.empty() ? "" : ", ") + name;
  for (const auto& name : arguments_) arguments += (arguments.empty() ? "" : ", ") + name;
  std::string code;
  if (!upvalues.empty()) code += "local " + upvalues + " = ...; ";
  code += "return function(" + arguments + ") return (" + body + ") end";

  lua_State* L = lua_.get();
  const int top = lua_gettop(L);
  if (luaL_loadbufferx(L, code.data(), code.size(), chunk_name.c_str(), "t") != LUA_OK) {
    const std::string message = lua_tostring(L, -1);
    lua_settop(L, top);
    throw InputError("expression '" + expression + "' does not compile: " + message);
  }
  for (const auto& name : used_builtins) lua_getglobal(L, name.c_str());
  for (const auto& name : used_identifiers) lua_pushnumber(L, identifiers.Value(name));
  const int n = static_cast<int>(used_builtins.size() + used_identifiers.size());
  if (lua_pcall(L, n, 1, 0) != LUA_OK || !lua_isfunction(L, -1)) {
    const std::string message = lua_isstring(L, -1) ? lua_tostring(L, -1) : "not a function";
    lua_settop(L, top);
    throw InputError("expression '" + expression + "': " + message);
  }
  function_ref_ = luaL_ref(L, LUA_REGISTRYINDEX);
  if (!lua_checkstack(L, num_arguments() + 4)) throw InputError("expression '" + expression + "': Lua stack full");
}

CompiledExpression::~CompiledExpression() { luaL_unref(lua_.get(), LUA_REGISTRYINDEX, function_ref_); }

double CompiledExpression::Evaluate(const double* args) const {
  lua_State* L = lua_.get();
  const int top = lua_gettop(L);
  lua_rawgeti(L, LUA_REGISTRYINDEX, function_ref_);
  for (int i = 0; i < num_arguments(); ++i) lua_pushnumber(L, args[i]);
  if (lua_pcall(L, num_arguments(), 1, 0) != LUA_OK) {
    const std::string message = lua_isstring(L, -1) ? lua_tostring(L, -1) : "error object is not a string";
    lua_settop(L, top);
    throw SimulationError(message);
  }
  int is_number = 0;
  const double value = lua_tonumberx(L, -1, &is_number);
  lua_settop(L, top);
  if (!is_number) throw SimulationError(label_ + ": expression '" + expression_ + "' did not give a number");
  if (!std::isfinite(value))
    throw SimulationError(label_ + ": expression '" + expression_ + "' gave " + std::to_string(value));
  return value;
}

}  // namespace mechflow::scripting
