#include "scripting/lua_state.h"

#include <cstdlib>
#include <stdexcept>

#include <lua.hpp>

namespace mechflow::scripting {
namespace {

// Run once in every state: the function names of the expression grammar.
const char kPrelude[] = R"lua(
local m = math
sin, cos, tan = m.sin, m.cos, m.tan
arcsin, arccos, arctan = m.asin, m.acos, m.atan
asin, acos, atan = m.asin, m.acos, m.atan
exp, ln, log, sqrt, abs = m.exp, m.log, m.log, m.sqrt, m.abs
floor, ceil, min, max = m.floor, m.ceil, m.min, m.max
pi = m.pi
function sqr(x) return x * x end
function sign(x) if x > 0 then return 1 elseif x < 0 then return -1 else return 0 end end
function sinh(x) return (m.exp(x) - m.exp(-x)) / 2 end
function cosh(x) return (m.exp(x) + m.exp(-x)) / 2 end
function tanh(x)
  if x > 20 then return 1 elseif x < -20 then return -1 end
  local e = m.exp(2 * x)
  return (e - 1) / (e + 1)
end
)lua";

// Text chunks only: precompiled bytecode can crash the interpreter.
const char kRestrictLoad[] = R"lua(
local raw_load = load
load = function(chunk, name, mode, env) return raw_load(chunk, name, "t", env) end
dofile, loadfile = nil, nil
)lua";

const char* const kBuiltins[] = {"sin",  "cos",  "tan", "arcsin", "arccos", "arctan", "asin", "acos",
                                 "atan", "exp",  "ln",  "log",    "sqrt",   "sqr",    "abs",  "sign",
                                 "min",  "max",  "floor", "ceil", "sinh",   "cosh",   "tanh", "pi"};

void RunOrThrow(lua_State* L, const char* code, const char* name) {
  if (luaL_loadbufferx(L, code, std::char_traits<char>::length(code), name, "t") != LUA_OK ||
      lua_pcall(L, 0, 0, 0) != LUA_OK) {
    const std::string message = lua_tostring(L, -1);
    lua_pop(L, 1);
    throw std::logic_error("Lua set-up failed: " + message);
  }
}

void InstructionHook(lua_State* L, lua_Debug*) {
  lua_sethook(L, nullptr, 0, 0);
  luaL_error(L, "instruction limit exceeded (endless loop?)");
}

}  // namespace

void* LuaState::Allocate(void* ud, void* ptr, std::size_t old_size, std::size_t new_size) {
  auto* memory = static_cast<Memory*>(ud);
  const std::size_t old_bytes = ptr ? old_size : 0;  // for new blocks old_size is a type tag
  if (new_size == 0) {
    std::free(ptr);
    memory->used -= old_bytes;
    return nullptr;
  }
  if (new_size > old_bytes && memory->used - old_bytes + new_size > memory->limit) return nullptr;
  void* block = std::realloc(ptr, new_size);
  if (block) memory->used = memory->used - old_bytes + new_size;
  return block;
}

LuaState::LuaState(bool unsafe) {
  L_ = lua_newstate(&LuaState::Allocate, &memory_);
  if (!L_) throw std::runtime_error("cannot create a Lua state");
  if (unsafe) {
    luaL_openlibs(L_);
  } else {
    const luaL_Reg libraries[] = {{LUA_GNAME, luaopen_base},       {LUA_MATHLIBNAME, luaopen_math},
                                  {LUA_STRLIBNAME, luaopen_string}, {LUA_TABLIBNAME, luaopen_table},
                                  {LUA_UTF8LIBNAME, luaopen_utf8}};
    for (const auto& lib : libraries) {
      luaL_requiref(L_, lib.name, lib.func, 1);
      lua_pop(L_, 1);
    }
    RunOrThrow(L_, kRestrictLoad, "=sandbox");
  }
  RunOrThrow(L_, kPrelude, "=prelude");
}

LuaState::~LuaState() {
  if (L_) lua_close(L_);
}

void LuaState::set_instruction_limit(long count) {
  if (count > 0) {
    lua_sethook(L_, &InstructionHook, LUA_MASKCOUNT, static_cast<int>(std::min<long>(count, 1L << 30)));
  } else {
    lua_sethook(L_, nullptr, 0, 0);
  }
}

bool LuaState::IsBuiltinName(std::string_view name) {
  for (const char* b : kBuiltins)
    if (name == b) return true;
  return false;
}

}  // namespace mechflow::scripting
