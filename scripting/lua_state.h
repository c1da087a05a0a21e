#pragma once
// LuaState: one sandboxed Lua 5.4 interpreter, owned RAII.
//
// Sandbox (default): only the base library (without dofile and loadfile, and
// with `load` restricted to text chunks), math, string, table and utf8. No io,
// os, require, package or debug: a diagram may come from someone else.
// `unsafe` opens every standard library (the user opted in on the command line).
//
// Also defined, for expressions written as in the model collection: sin cos tan
// arcsin arccos arctan asin acos atan exp ln log sqrt sqr abs sign min max
// floor ceil sinh cosh tanh pi.
//
// Memory is capped by a counting allocator; an instruction limit can be armed
// around code that must not hang (load-time evaluation).

#include <cstddef>
#include <string>
#include <string_view>

struct lua_State;

namespace mechflow::scripting {

class LuaState {
 public:
  explicit LuaState(bool unsafe = false);
  ~LuaState();
  LuaState(const LuaState&) = delete;
  LuaState& operator=(const LuaState&) = delete;

  lua_State* get() const { return L_; }

  // Bytes Lua may hold in all (default 256 MiB); allocations past it fail.
  void set_memory_limit(std::size_t bytes) { memory_.limit = bytes; }
  std::size_t memory_in_use() const { return memory_.used; }

  // Raises "instruction limit exceeded" in Lua code after `count` VM
  // instructions from now; 0 removes the limit.
  void set_instruction_limit(long count);

  // Names defined by the sandbox for expressions (sin, ln, pi, ...).
  static bool IsBuiltinName(std::string_view name);

 private:
  struct Memory {
    std::size_t used = 0;
    std::size_t limit = std::size_t(256) << 20;
  };
  static void* Allocate(void* ud, void* ptr, std::size_t old_size, std::size_t new_size);

  Memory memory_;
  lua_State* L_ = nullptr;
};

// Arms an instruction limit for the lifetime of the guard.
class InstructionLimit {
 public:
  InstructionLimit(LuaState& lua, long count) : lua_(lua) { lua_.set_instruction_limit(count); }
  ~InstructionLimit() { lua_.set_instruction_limit(0); }

 private:
  LuaState& lua_;
};

}  // namespace mechflow::scripting
