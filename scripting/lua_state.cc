#include "scripting/lua_state.h"

#include <algorithm>
#include <chrono>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <stdexcept>

#include <lua.hpp>

#include "blocks/support/excerpt.h"
#include "mech/errors.h"
#include "scripting/lua_guards.h"

namespace mechflow::scripting {
namespace {

// A Lua error message with its traceback fits in this many characters.
constexpr std::size_t kMaxErrorLength = 2000;

// Every function below is called by Lua and may raise a Lua error (a
// long jump): none may own a C++ object with a destructor.

// Registry field: the set of the sandbox's own functions of numbers.
constexpr const char* kPureFunctionsKey = "mechflow.pure_functions";

// The LuaState that owns L (kept in Lua's extra space for the hook).
LuaState& OwnerOf(lua_State* L) { return **static_cast<LuaState**>(lua_getextraspace(L)); }

double Now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// load(chunk [, chunkname [, mode [, env]]]) with mode forced to "t":
// precompiled bytecode is not checked by Lua and can crash the interpreter.
int TextOnlyLoad(lua_State* L) {
  const int n = std::max(lua_gettop(L), 3);  // keeps env absent when it was
  lua_settop(L, n);
  lua_pushliteral(L, "t");
  lua_replace(L, 3);
  lua_pushvalue(L, lua_upvalueindex(1));  // the original load
  lua_insert(L, 1);
  lua_call(L, n, LUA_MULTRET);
  return lua_gettop(L);
}

// the expression functions that Lua's math library lacks
int Sqr(lua_State* L) {
  const lua_Number x = luaL_checknumber(L, 1);
  lua_pushnumber(L, x * x);
  return 1;
}
int Sign(lua_State* L) {
  const lua_Number x = luaL_checknumber(L, 1);
  lua_pushnumber(L, x > 0 ? 1.0 : x < 0 ? -1.0 : x == 0 ? 0.0 : x);  // NaN stays NaN
  return 1;
}
// STEP(x, x0, h0, x1, h1): h0 up to x0, h1 from x1 on, a cubic
// h0 + (h1 - h0) D^2 (3 - 2 D), D = (x - x0)/(x1 - x0), between -- the smooth
// step of ADAMS-type codes and of the tension-mechanism paper. x1 = x0 is a
// jump at x0 (h0 there); x1 < x0 is an error.
int Step(lua_State* L) {
  const lua_Number x = luaL_checknumber(L, 1), x0 = luaL_checknumber(L, 2), h0 = luaL_checknumber(L, 3),
                   x1 = luaL_checknumber(L, 4), h1 = luaL_checknumber(L, 5);
  if (x1 < x0) return luaL_error(L, "STEP: x1 (%f) is below x0 (%f)", x1, x0);
  if (!(x > x0)) {
    lua_pushnumber(L, x == x0 || x < x0 ? h0 : x);  // NaN stays NaN
    return 1;
  }
  if (x >= x1) {
    lua_pushnumber(L, h1);
    return 1;
  }
  const lua_Number d = (x - x0) / (x1 - x0);
  lua_pushnumber(L, h0 + (h1 - h0) * d * d * (3 - 2 * d));
  return 1;
}
int Sinh(lua_State* L) {
  lua_pushnumber(L, std::sinh(luaL_checknumber(L, 1)));
  return 1;
}
int Cosh(lua_State* L) {
  lua_pushnumber(L, std::cosh(luaL_checknumber(L, 1)));
  return 1;
}
int Tanh(lua_State* L) {
  lua_pushnumber(L, std::tanh(luaL_checknumber(L, 1)));
  return 1;
}

// global name = math field, for the names of the expression grammar
struct Alias {
  const char* global;
  const char* math_field;
};
constexpr Alias kMathAliases[] = {
    {"sin", "sin"},     {"cos", "cos"},     {"tan", "tan"},     {"arcsin", "asin"}, {"arccos", "acos"},
    {"arctan", "atan"}, {"asin", "asin"},   {"acos", "acos"},   {"atan", "atan"},   {"exp", "exp"},
    {"ln", "log"},      {"log", "log"},     {"sqrt", "sqrt"},   {"abs", "abs"},     {"min", "min"},
    {"max", "max"},     {"floor", "floor"}, {"ceil", "ceil"},   {"pi", "pi"},
};
constexpr luaL_Reg kExtraFunctions[] = {
    {"sqr", Sqr}, {"sign", Sign}, {"STEP", Step}, {"sinh", Sinh}, {"cosh", Cosh}, {"tanh", Tanh},
};

// Sets up the sandbox and the expression names; run in protected mode.
int SetUp(lua_State* L) {
  const bool unsafe = lua_toboolean(L, 1);
  if (unsafe) {
    luaL_openlibs(L);
  } else {
    // io, os, package/require, debug and coroutine are left out on purpose
    constexpr luaL_Reg kLibraries[] = {{LUA_GNAME, luaopen_base},       {LUA_MATHLIBNAME, luaopen_math},
                                       {LUA_STRLIBNAME, luaopen_string}, {LUA_TABLIBNAME, luaopen_table},
                                       {LUA_UTF8LIBNAME, luaopen_utf8}};
    for (const auto& library : kLibraries) {
      luaL_requiref(L, library.name, library.func, 1);
      lua_pop(L, 1);
    }
    lua_pushnil(L);
    lua_setglobal(L, "dofile");
    lua_pushnil(L);
    lua_setglobal(L, "loadfile");
  }
  lua_getglobal(L, "load");
  lua_pushcclosure(L, &TextOnlyLoad, 1);
  lua_setglobal(L, "load");
  InstallLuaGuards(L, OwnerOf(L).memory_limit());

  lua_getglobal(L, LUA_MATHLIBNAME);
  for (const Alias& alias : kMathAliases) {
    lua_getfield(L, -1, alias.math_field);
    lua_setglobal(L, alias.global);
  }
  lua_pop(L, 1);
  for (const luaL_Reg& f : kExtraFunctions) {
    lua_pushcfunction(L, f.func);
    lua_setglobal(L, f.name);
  }
  // the functions of numbers just set up, as keys (IsPureFunction)
  lua_newtable(L);
  const auto add = [L](const char* name) {
    if (lua_getglobal(L, name) != LUA_TFUNCTION) {  // pi
      lua_pop(L, 1);
      return;
    }
    lua_pushboolean(L, 1);
    lua_rawset(L, -3);
  };
  for (const Alias& alias : kMathAliases) add(alias.global);
  for (const luaL_Reg& f : kExtraFunctions) add(f.name);
  lua_setfield(L, LUA_REGISTRYINDEX, kPureFunctionsKey);
  return 0;
}

int Panic(lua_State* L) {
  const char* message = lua_tostring(L, -1);
  std::fprintf(stderr, "mechflow: unprotected Lua error (%s)\n", message ? message : "no message");
  return 0;  // Lua aborts
}

}  // namespace

// Called by Lua (may long-jump): owns no C++ object with a destructor.
void LuaState::InstructionHook(lua_State* L, lua_Debug*) {
  LuaState* lua = &OwnerOf(L);
  CallBudget& call = lua->call_;
  if (call.exceeded == Exceeded::kNone) {
    call.instructions += call.interval;
    if (lua->instruction_limit_ > 0 && call.instructions >= lua->instruction_limit_) {
      call.exceeded = Exceeded::kInstructions;
    } else if (lua->time_limit_ > 0.0 && Now() - call.start > lua->time_limit_) {
      call.exceeded = Exceeded::kTime;
    } else {
      return;
    }
    // from now on every instruction raises the error again: whatever a
    // script catches, no Lua code runs on until the call returns
    lua_sethook(L, &InstructionHook, LUA_MASKCOUNT, 1);
  }
  luaL_where(L, 0);  // in a hook, level 0 is the Lua function that was running
  if (call.exceeded == Exceeded::kInstructions) {
    lua_pushfstring(L, "instruction limit exceeded (%I instructions in one call; endless loop?)",
                    static_cast<lua_Integer>(lua->instruction_limit_));
  } else if (call.exceeded == Exceeded::kTime) {
    lua_pushfstring(L, "time limit exceeded (one call may run for %f s)", lua->time_limit_);
  } else {
    lua_pushstring(L, lua->refusal_);
  }
  lua_concat(L, 2);
  lua_error(L);
}

void* LuaState::Allocate(void* ud, void* ptr, std::size_t old_size, std::size_t new_size) {
  auto* memory = static_cast<Memory*>(ud);
  const std::size_t old_bytes = ptr ? old_size : 0;  // for new blocks old_size is a type tag
  if (new_size == 0) {
    std::free(ptr);
    memory->used -= old_bytes;
    return nullptr;
  }
  if (new_size > old_bytes && memory->used - old_bytes + new_size > memory->limit) {
    // Lua collects the whole heap before it gives up: a loop of refused
    // allocations is a loop of full collections
    if (memory->owner) memory->owner->HurryTimeCheck();
    return nullptr;
  }
  void* block = std::realloc(ptr, new_size);
  if (block) memory->used = memory->used - old_bytes + new_size;
  if (block && new_size >= kLargeBlock && memory->owner) memory->owner->HurryTimeCheck();
  return block;
}

void LuaState::HurryTimeCheck() {
  // lua_sethook may be called anywhere (the standalone interpreter calls it
  // from a signal handler); the hook then raises the error
  if (!L_ || time_limit_ <= 0.0 || call_.exceeded != Exceeded::kNone || call_.interval == 1 || !lua_gethook(L_)) return;
  if (Now() - call_.start <= time_limit_) return;
  call_.interval = 1;
  lua_sethook(L_, &InstructionHook, LUA_MASKCOUNT, 1);
}

LuaState::LuaState(Options options) : unsafe_(options.unsafe) {
  memory_.limit = options.memory_limit;
  memory_.owner = this;
  set_instruction_limit(options.instruction_limit);
  set_time_limit(options.time_limit);
  L_ = lua_newstate(&LuaState::Allocate, &memory_);
  if (!L_) throw std::runtime_error("cannot create a Lua state (out of memory)");
  *static_cast<LuaState**>(lua_getextraspace(L_)) = this;  // for the hook
  lua_atpanic(L_, &Panic);
  lua_pushcfunction(L_, &SetUp);
  lua_pushboolean(L_, unsafe_);
  std::string error;
  if (!Call(1, 0, &error)) {
    lua_close(L_);
    throw std::runtime_error("cannot set up Lua: " + error);
  }
}

LuaState::~LuaState() {
  if (L_) lua_close(L_);
}

LuaState::RunClaim LuaState::ClaimForRun() {
  const std::lock_guard<std::mutex> lock(claim_mutex_);
  const std::thread::id me = std::this_thread::get_id();
  if (claims_ > 0 && claim_thread_ != me)
    throw SimulationError("the diagram's Lua state (its Lua blocks, expressions and control script) is in use by a "
                          "run on another thread, and one Lua state cannot run on two threads at once: load the "
                          "diagram once per thread to run it on several");
  claim_thread_ = me;
  ++claims_;
  return RunClaim(this);
}

LuaState::RunClaim::~RunClaim() {
  if (!state_) return;
  const std::lock_guard<std::mutex> lock(state_->claim_mutex_);
  --state_->claims_;
}

void LuaState::Arm() {
  call_ = {};
  call_.start = Now();
  if (instruction_limit_ > 0) call_.interval = static_cast<int>(std::min<long>(instruction_limit_, kCheckInterval));
  lua_sethook(L_, &InstructionHook, LUA_MASKCOUNT, call_.interval);
}

BoundedCall::BoundedCall(LuaState& lua) : L_(lua.get()) {
  // a hook already set means an enclosing call is bounded (ours is removed
  // when that call returns)
  if ((lua.instruction_limit_ > 0 || lua.time_limit_ > 0.0) && !lua_gethook(L_)) {
    lua.Arm();
    armed_ = true;
  }
}

BoundedCall::~BoundedCall() {
  if (!armed_) return;
  lua_sethook(L_, nullptr, 0, 0);
  OwnerOf(L_).call_.exceeded = LuaState::Exceeded::kNone;
}

StraightLineCall::~StraightLineCall() {
  if (!lua_.call_.armed_midway) return;
  lua_sethook(lua_.get(), nullptr, 0, 0);
  lua_.call_ = {};
}

// Called by Lua (may long-jump): owns no C++ object with a destructor.
void LuaState::BoundFromHere(lua_State* L) {
  LuaState& lua = OwnerOf(L);
  if (lua_gethook(L) || (lua.instruction_limit_ <= 0 && lua.time_limit_ <= 0.0)) return;
  lua.Arm();  // Lua sets the running functions' traps: the hook counts from the next instruction
  lua.call_.armed_midway = true;
}

// Called by Lua (long-jumps): owns no C++ object with a destructor.
int LuaState::RaiseLimit(lua_State* L, const char* text) {
  LuaState& lua = OwnerOf(L);
  if (lua_gethook(L) && lua.call_.exceeded == Exceeded::kNone) {
    std::snprintf(lua.refusal_, sizeof lua.refusal_, "%s", text);
    lua.call_.exceeded = Exceeded::kRefused;
    lua_sethook(L, &InstructionHook, LUA_MASKCOUNT, 1);
  }
  luaL_where(L, 1);  // the line that called the guarded function
  lua_pushstring(L, text);
  lua_concat(L, 2);
  return lua_error(L);
}

void LuaState::CheckTimeSoon(lua_State* L) { OwnerOf(L).HurryTimeCheck(); }

bool LuaState::LimitPassed(lua_State* L) {
  return OwnerOf(L).call_.exceeded != Exceeded::kNone;
}

bool LuaState::IsPureFunction(lua_State* L, int index) {
  if (!lua_iscfunction(L, index)) return false;
  index = lua_absindex(L, index);
  lua_getfield(L, LUA_REGISTRYINDEX, kPureFunctionsKey);
  lua_pushvalue(L, index);
  const bool pure = lua_rawget(L, -2) == LUA_TBOOLEAN;
  lua_pop(L, 2);
  return pure;
}

std::string LuaState::ErrorText(int status) const {
  std::string text;
  if (const char* message = lua_tostring(L_, -1)) {
    // the code may be someone else's: its message may be huge or hold control characters
    text = blocks::MessageExcerpt(message, kMaxErrorLength);
  } else {
    text = std::string("(error object is a ") + luaL_typename(L_, -1) + " value)";
  }
  if (status == LUA_ERRMEM)
    text += " (Lua may use at most " + std::to_string(memory_.limit >> 20) + " MiB)";
  return text;
}

bool LuaState::Call(int num_args, int num_results, std::string* error) {
  const int handler = lua_gettop(L_) - num_args;  // where the function is now
  lua_pushcfunction(L_, &TracebackHandler);
  lua_insert(L_, handler);
  int status;
  {
    BoundedCall bounded(*this);
    status = lua_pcall(L_, num_args, num_results, handler);
  }
  lua_remove(L_, handler);
  if (status == LUA_OK) return true;
  if (error) *error = ErrorText(status);
  lua_pop(L_, 1);
  return false;
}

bool LuaState::Run(std::string_view code, const std::string& chunk_name, std::string* error) {
  if (std::string problem = CompileCostProblem(code); !problem.empty()) {
    const bool named = !chunk_name.empty() && (chunk_name[0] == '@' || chunk_name[0] == '=');
    if (error) *error = (named ? chunk_name.substr(1) : chunk_name) + ": " + problem;
    return false;
  }
  const int status = luaL_loadbufferx(L_, code.data(), code.size(), chunk_name.c_str(), "t");
  if (status != LUA_OK) {
    if (error) *error = ErrorText(status);
    lua_pop(L_, 1);
    return false;
  }
  return Call(0, 0, error);
}

int LuaState::TracebackHandler(lua_State* L) {
  const char* message = lua_tostring(L, 1);
  if (!message) {
    if (luaL_callmeta(L, 1, "__tostring") && lua_type(L, -1) == LUA_TSTRING) {
      message = lua_tostring(L, -1);
    } else {
      message = lua_pushfstring(L, "(error object is a %s value)", luaL_typename(L, 1));
    }
  }
  luaL_traceback(L, L, message, 1);
  return 1;
}

bool LuaState::IsBuiltinName(std::string_view name) {
  for (const Alias& alias : kMathAliases)
    if (name == alias.global) return true;
  for (const luaL_Reg& f : kExtraFunctions)
    if (name == f.name) return true;
  return false;
}

std::vector<std::string> LuaState::BuiltinNames() {
  std::vector<std::string> names;
  for (const Alias& alias : kMathAliases) names.push_back(alias.global);
  for (const luaL_Reg& f : kExtraFunctions) names.push_back(f.name);
  return names;
}

}  // namespace mechflow::scripting
