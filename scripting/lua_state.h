#pragma once
// LuaState: one sandboxed Lua 5.4 interpreter, owned RAII.
//
// Sandbox (default): only the base library (without dofile and loadfile, and
// with `load` restricted to text chunks), math, string, table and utf8. No io,
// os, require, package, debug or coroutine: a diagram may come from someone
// else. `unsafe` opens every standard library (the user opted in on the
// command line); `load` still refuses bytecode, which can crash the VM.
//
// Also defined as globals, for expressions written as in the model collection
// (ELEMENTS.md 1.1): sin cos tan arcsin arccos arctan asin acos atan exp ln log
// sqrt sqr abs sign min max floor ceil sinh cosh tanh pi. `^` is Lua's power
// operator (right-associative, always a float).
//
// Limits:
//   - memory: a counting allocator refuses to grow Lua's heap past the limit
//     (default 256 MiB); the script sees the error "not enough memory".
//   - instructions: set_instruction_limit(n) makes Lua code raise
//     "instruction limit exceeded" after n VM instructions. A script cannot
//     swallow it with pcall: once exceeded, the error is raised again every
//     1000 instructions until the limit is removed. Armed by callers around
//     code that must not hang (load-time evaluation).
//
// Lua errors long-jump: no C++ frame owning resources may sit between a
// lua_pcall and the code that raises. Every call into Lua from C++ goes
// through a protected call (Call, Run, or lua_pcall directly).

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

struct lua_State;

namespace mechflow::scripting {

class LuaState {
 public:
  explicit LuaState(bool unsafe = false);
  ~LuaState();
  LuaState(const LuaState&) = delete;
  LuaState& operator=(const LuaState&) = delete;

  lua_State* get() const { return L_; }
  bool is_unsafe() const { return unsafe_; }

  // Bytes Lua may hold in all (default 256 MiB); allocations past it fail.
  void set_memory_limit(std::size_t bytes) { memory_.limit = bytes; }
  std::size_t memory_limit() const { return memory_.limit; }
  std::size_t memory_in_use() const { return memory_.used; }

  // Raises "instruction limit exceeded" in Lua code after `count` VM
  // instructions from now; 0 (or less) removes the limit.
  void set_instruction_limit(long count);

  // Calls the function lying below `num_args` arguments on the stack in
  // protected mode, with TracebackHandler as message handler. On success
  // leaves `num_results` results (LUA_MULTRET: all) and returns true. On
  // failure removes the function and arguments, stores the message (with a
  // traceback) in *error and returns false.
  bool Call(int num_args, int num_results, std::string* error);

  // Loads `code` as a text chunk named `chunk_name` ("@file.lua" gives
  // messages "file.lua:12: ...", "=name" gives "name:12: ...") and runs it
  // with no results. Returns false with the message in *error on a syntax or
  // run-time error.
  bool Run(std::string_view code, const std::string& chunk_name, std::string* error);

  // The text of the error value on top of the stack after a failed call that
  // returned `status`; "not enough memory" gets the limit added. Does not pop.
  std::string ErrorText(int status) const;

  // Message handler for lua_pcall, as in lua.c: turns a non-string error
  // object into text (its __tostring, or "(error object is a T value)") and
  // appends a stack traceback.
  static int TracebackHandler(lua_State* L);

  // Names defined by the sandbox for expressions (sin, ln, pi, ...).
  static bool IsBuiltinName(std::string_view name);
  static std::vector<std::string> BuiltinNames();

 private:
  struct Memory {
    std::size_t used = 0;
    std::size_t limit = std::size_t(256) << 20;
  };
  static void* Allocate(void* ud, void* ptr, std::size_t old_size, std::size_t new_size);

  Memory memory_;
  bool unsafe_ = false;
  lua_State* L_ = nullptr;
};

// Arms an instruction limit for the lifetime of the guard.
class InstructionLimit {
 public:
  InstructionLimit(LuaState& lua, long count) : lua_(lua) { lua_.set_instruction_limit(count); }
  ~InstructionLimit() { lua_.set_instruction_limit(0); }
  InstructionLimit(const InstructionLimit&) = delete;
  InstructionLimit& operator=(const InstructionLimit&) = delete;

 private:
  LuaState& lua_;
};

}  // namespace mechflow::scripting
