#include "scripting/compiled_expression.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>

#include <lua.hpp>

#include "blocks/support/excerpt.h"
#include "blocks/support/suggest.h"
#include "mech/errors.h"
#include "scripting/identifier_bindings.h"
#include "scripting/identifiers.h"
#include "scripting/lua_guards.h"
#include "scripting/lua_lexer.h"
#include "scripting/lua_state.h"

namespace mechflow::scripting {
namespace {

// The free names of an expression, and the expression with identifier names
// in their canonical lower case.
struct Scan {
  std::string rewritten;
  std::vector<std::string> free_names;  // in order of first use, after rewriting
  bool defines_function = false;
};

Scan ScanExpression(const std::string& expr, const IdentifierTable& identifiers) {
  Scan scan;
  std::string previous;  // previous token if it was punctuation, else ""
  for (std::size_t i = 0, end = 0; i < expr.size(); i = end) {
    const LuaToken kind = NextLuaToken(expr, i, &end);
    if (kind == LuaToken::kName) {
      std::string name = expr.substr(i, end - i);
      std::size_t next = end;
      while (next < expr.size() && std::isspace(static_cast<unsigned char>(expr[next]))) ++next;
      const bool field = previous == "." || previous == ":";
      const bool key = next < expr.size() && expr[next] == '=' && (next + 1 == expr.size() || expr[next + 1] != '=');
      if (!IsLuaName(name)) {  // a keyword
        scan.defines_function |= name == "function";
      } else if (!field && !key) {
        if (identifiers.Has(name)) name = ToLower(name);
        if (std::find(scan.free_names.begin(), scan.free_names.end(), name) == scan.free_names.end())
          scan.free_names.push_back(name);
      }
      scan.rewritten += name;
      previous.clear();
      continue;
    }
    if (kind == LuaToken::kPunctuation) previous = expr.substr(i, end - i);
    if (kind == LuaToken::kString || kind == LuaToken::kNumber) previous.clear();
    scan.rewritten.append(expr, i, end - i);
  }
  return scan;
}

// Message handler of an expression (upvalue 1: its chunk name). Turns any
// error object into text; adds a traceback only when Lua code from another
// chunk (a function a script defined) was running, since the expression's own
// position is already in the message.
int ExpressionMessageHandler(lua_State* L) {
  const char* chunk = lua_tostring(L, lua_upvalueindex(1));
  bool foreign = false;
  lua_Debug ar;
  for (int level = 1; lua_getstack(L, level, &ar); ++level) {
    lua_getinfo(L, "S", &ar);
    if (std::strcmp(ar.what, "C") == 0) continue;
    if (std::strcmp(ar.source, chunk) == 0) break;  // reached the expression
    foreign = true;
  }
  if (foreign) return LuaState::TracebackHandler(L);
  if (lua_type(L, 1) == LUA_TSTRING) return 1;
  if (luaL_callmeta(L, 1, "__tostring") && lua_type(L, -1) == LUA_TSTRING) return 1;
  lua_pushfstring(L, "(error object is a %s value)", luaL_typename(L, 1));
  return 1;
}

std::string Join(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& name : names) out += (out.empty() ? "" : ", ") + name;
  return out;
}

}  // namespace

CompiledExpression::CompiledExpression(LuaState& lua, const std::string& expression,
                                       std::vector<std::string> argument_names, const IdentifierTable& identifiers,
                                       const std::string& chunk_name)
    : lua_(lua),
      expression_(expression),
      label_(!chunk_name.empty() && (chunk_name[0] == '=' || chunk_name[0] == '@') ? chunk_name.substr(1)
                                                                                   : chunk_name),
      arguments_(std::move(argument_names)) {
  lua_.NoteRunTimeCode();  // evaluated during runs: they must claim the state
  for (std::size_t i = 0; i < arguments_.size(); ++i) {
    if (!IsLuaName(arguments_[i]))
      throw InputError(label_ + ": argument name '" + arguments_[i] + "' is not a Lua name");
    if (std::find(arguments_.begin(), arguments_.begin() + i, arguments_[i]) != arguments_.begin() + i)
      throw InputError(label_ + ": argument name '" + arguments_[i] + "' is given twice");
    // identifiers are case-insensitive, arguments are not: `U` would be ambiguous
    if (const int id = identifiers.Find(arguments_[i]); id >= 0)
      throw InputError(label_ + ": argument name '" + arguments_[i] + "' is also the name of the identifier '" +
                       identifiers.spelling(id) + "' (" + identifiers.origin(id) + "); rename one of them");
  }
  lua_State* L = lua_.get();
  const int top = lua_gettop(L);

  if (const std::string problem = CompileCostProblem(expression); !problem.empty())
    throw InputError(label_ + ": expression '" + expression.substr(0, 80) + (expression.size() > 80 ? "...'" : "'") +
                     ": " + problem);
  // syntax, checked on the text as written so Lua's message quotes it
  const std::string alone = "return " + expression;
  int status = luaL_loadbufferx(L, alone.data(), alone.size(), chunk_name.c_str(), "t");
  if (status != LUA_OK) {
    const std::string message = lua_.ErrorText(status);
    lua_settop(L, top);
    throw InputError("expression '" + blocks::Excerpt(expression) + "' does not compile: " + message);
  }
  lua_settop(L, top);

  // resolve every free name: argument, identifier, existing global, or error
  const Scan scan = ScanExpression(expression, identifiers);
  std::vector<std::string> upvalues;
  std::vector<std::string> unknown;
  for (const auto& name : scan.free_names) {
    if (std::find(arguments_.begin(), arguments_.end(), name) != arguments_.end()) continue;
    if (identifiers.Has(name)) {
      identifiers_used_.push_back(name);
      upvalues.push_back(name);
      continue;
    }
    const bool exists = lua_getglobal(L, name.c_str()) != LUA_TNIL;
    lua_settop(L, top);
    if (exists) {
      upvalues.push_back(name);
    } else if (!scan.defines_function) {
      unknown.push_back(name);
    }
  }
  if (!unknown.empty()) {
    std::vector<std::string> candidates = arguments_;
    for (const auto& name : identifiers.Names()) candidates.push_back(name);
    for (const auto& name : LuaState::BuiltinNames()) candidates.push_back(name);
    // a one-letter name is close to too many others for a suggestion to help
    const std::string& name = unknown.front();
    throw InputError("expression '" + blocks::Excerpt(expression) + "' uses the unknown name '" + name + "'" +
                     (name.size() > 1 ? blocks::DidYouMean(name, candidates) : "") +
                     (arguments_.empty() ? "; it has no arguments" : "; its arguments are " + Join(arguments_)));
  }

  // the chunk: upvalues as locals set from its arguments, then the function
  std::string code;
  if (!upvalues.empty()) code += "local " + Join(upvalues) + " = ...; ";
  code += "return function(" + Join(arguments_) + ") return (" + scan.rewritten + "\n) end";
  status = luaL_loadbufferx(L, code.data(), code.size(), chunk_name.c_str(), "t");
  if (status != LUA_OK) {
    const std::string message = lua_.ErrorText(status);
    lua_settop(L, top);
    throw InputError("expression '" + blocks::Excerpt(expression) + "' does not compile as one expression: " + message);
  }
  if (!lua_checkstack(L, static_cast<int>(upvalues.size()) + 2)) {
    lua_settop(L, top);
    throw InputError("expression '" + blocks::Excerpt(expression) + "' uses too many names");
  }
  bounded_ = scan.defines_function || scan.rewritten.find_first_of("\"'[:") != std::string::npos;
  for (const auto& name : upvalues) {
    if (identifiers.Has(name)) {
      lua_pushnumber(L, identifiers.Value(name));
    } else {
      // any other C function may call what it is given (pcall, load with a
      // reader), and a table or userdata may have metatables of a script
      lua_getglobal(L, name.c_str());
      if (lua_type(L, -1) != LUA_TNUMBER && !LuaState::IsPureFunction(L, -1)) bounded_ = true;
    }
  }
  if (bounded_) lua_.NoteCodeThatMayKeepState();
  std::string error;
  if (!lua_.Call(static_cast<int>(upvalues.size()), 1, &error) || !lua_isfunction(L, -1)) {
    lua_settop(L, top);
    throw InputError("expression '" + blocks::Excerpt(expression) +
                     "': " + (error.empty() ? "did not compile to a function" : error));
  }
  if (!identifiers_used_.empty()) BindIdentifiers(L, -1);
  function_ref_ = luaL_ref(L, LUA_REGISTRYINDEX);
  lua_pushstring(L, chunk_name.c_str());
  lua_pushcclosure(L, &ExpressionMessageHandler, 1);
  handler_ref_ = luaL_ref(L, LUA_REGISTRYINDEX);
}

CompiledExpression::~CompiledExpression() {
  luaL_unref(lua_.get(), LUA_REGISTRYINDEX, function_ref_);
  luaL_unref(lua_.get(), LUA_REGISTRYINDEX, handler_ref_);
}

double CompiledExpression::Evaluate(const double* args) const {
  lua_State* L = lua_.get();
  const int n = num_arguments();
  const int top = lua_gettop(L);
  if (!lua_checkstack(L, n + 2)) throw SimulationError(label_ + ": Lua stack overflow");
  lua_rawgeti(L, LUA_REGISTRYINDEX, handler_ref_);
  lua_rawgeti(L, LUA_REGISTRYINDEX, function_ref_);
  for (int i = 0; i < n; ++i) lua_pushnumber(L, args[i]);
  int status;
  if (bounded_) {
    BoundedCall bounded(lua_);
    status = lua_pcall(L, n, 1, top + 1);
  } else {
    status = lua_pcall(L, n, 1, top + 1);
  }
  if (status != LUA_OK) {
    const std::string message = lua_.ErrorText(status);
    lua_settop(L, top);
    throw SimulationError(label_ + ": expression error" + (n > 0 ? " " + DescribeArguments(args) : "") + ": " +
                          message);
  }
  const int type = lua_type(L, -1);
  const double value = lua_tonumber(L, -1);
  lua_settop(L, top);
  if (type != LUA_TNUMBER)
    throw SimulationError(label_ + ": expression '" + blocks::Excerpt(expression_) + "' gives a " +
                          lua_typename(L, type) +
                          ", not a number" + (n > 0 ? ", " + DescribeArguments(args) : "") +
                          (type == LUA_TBOOLEAN ? " (write 'cond and 1 or 0' for a number)" : ""));
  if (!std::isfinite(value))
    throw SimulationError(label_ + ": expression '" + blocks::Excerpt(expression_) + "' gives " +
                          std::to_string(value) +
                          (n > 0 ? " " + DescribeArguments(args) : ""));
  return value;
}

std::string CompiledExpression::DescribeArguments(const double* args) const {
  std::string out = "at";
  for (int i = 0; i < num_arguments(); ++i) {
    char value[32];
    std::snprintf(value, sizeof value, "%.6g", args[i]);
    out += (i ? ", " : " ") + arguments_[i] + " = " + value;
  }
  return out;
}

}  // namespace mechflow::scripting
