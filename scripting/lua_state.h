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
// Limits (LuaState::Options, both adjustable later):
//   - memory: a counting allocator refuses to grow Lua's heap past the limit
//     (default 256 MiB); the script sees the error "not enough memory", the
//     caller "not enough memory (Lua may use at most 256 MiB)".
//   - instructions: each protected call from C++ (Call, Run, or a lua_pcall
//     inside a BoundedCall) may run at most instruction_limit VM instructions
//     (default 10 million, about 0.1 s); then Lua raises "chunk:line:
//     instruction limit exceeded (...)".
//   - time: the same call may take at most time_limit seconds of wall-clock
//     time (default 5 s), a backstop for Lua code that spends its time in C
//     functions (each one VM instruction); then "time limit exceeded".
//   A script cannot swallow either error with pcall: once a limit is passed,
//   the error is raised again at every instruction until the call returns,
//   so no Lua code can run on. Both are checked by a count hook (every
//   kCheckInterval instructions), armed at the start of the call and removed
//   at its end, so there is no cost between calls; a large allocation (or a
//   refused one, after which Lua collects the whole heap) past the time limit
//   makes the hook run at the next instruction. C functions whose work the
//   count cannot see are guarded separately (scripting/lua_guards.h); a
//   guard's refusal (RaiseLimit) is raised again like a limit's error.
//
// One interpreter, one thread: a diagram's Lua blocks, expressions
// (expression blocks, mechanism laws and parameters that follow inputs) and
// control script share the one state its load made. A run of such a diagram
// claims the state (ClaimForRun, when the run's Context is prepared) for as
// long as its Context lives; a claim from another thread meanwhile is refused
// (SimulationError: load the diagram once per thread). Runs without Lua at
// run time share nothing and may run on several threads at once.
//
// Lua errors long-jump: no C++ frame owning resources may sit between a
// lua_pcall and the code that raises. Every call into Lua from C++ goes
// through a protected call (Call, Run, or lua_pcall directly).

#include <algorithm>
#include <climits>
#include <cstddef>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <string_view>
#include <vector>

struct lua_State;
struct lua_Debug;

namespace mechflow::scripting {

class LuaState {
 public:
  struct Options {
    bool unsafe = false;                                // every standard library
    std::size_t memory_limit = std::size_t(256) << 20;  // bytes of Lua heap
    long instruction_limit = 10'000'000;                // per call from C++; 0: none
    double time_limit = 5.0;                            // s of wall-clock time per call; 0: none
  };

  // Instructions between two looks at the limits.
  // Often enough that a loop of slow C calls meets the time limit on time;
  // the hook's call costs little next to the per-instruction count itself.
  static constexpr int kCheckInterval = 1000;

  explicit LuaState(Options options);
  LuaState() : LuaState(Options{}) {}
  ~LuaState();
  LuaState(const LuaState&) = delete;
  LuaState& operator=(const LuaState&) = delete;

  lua_State* get() const { return L_; }
  bool is_unsafe() const { return unsafe_; }

  // Code compiled into the state that runs during a diagram's runs (a Lua
  // block, a compiled expression): its runs must claim the state.
  void NoteRunTimeCode() { ++run_time_code_; }
  bool has_run_time_code() const { return run_time_code_ > 0; }
  // Of that, code that may keep something from one call to the next (a Lua
  // block; an expression that calls what is not a pure function of numbers):
  // a second run of the diagram could start from what the first left.
  void NoteCodeThatMayKeepState() { ++stateful_code_; }
  bool has_code_that_may_keep_state() const { return stateful_code_ > 0; }

  // Held by one run (of this state's diagram) while it lasts; movable.
  class RunClaim {
   public:
    RunClaim(RunClaim&& other) noexcept : state_(std::exchange(other.state_, nullptr)) {}
    RunClaim& operator=(RunClaim&&) = delete;
    ~RunClaim();

   private:
    friend class LuaState;
    explicit RunClaim(LuaState* state) : state_(state) {}
    LuaState* state_;
  };
  // Claims the state for a run on this thread. Throws SimulationError when a
  // run on another thread holds it: the state is one, so such runs would
  // race in it. Claims on one thread nest (an analysis next to a run).
  RunClaim ClaimForRun();

  // Bytes Lua may hold in all (default 256 MiB); allocations past it fail.
  void set_memory_limit(std::size_t bytes) { memory_.limit = bytes; }
  std::size_t memory_limit() const { return memory_.limit; }
  std::size_t memory_in_use() const { return memory_.used; }

  // VM instructions one protected call from C++ may run; 0 (or less): any.
  void set_instruction_limit(long count) { instruction_limit_ = count > 0 ? std::min<long>(count, INT_MAX) : 0; }
  long instruction_limit() const { return instruction_limit_; }

  // Seconds of wall-clock time one protected call from C++ may take; 0: any.
  void set_time_limit(double seconds) { time_limit_ = seconds > 0.0 ? seconds : 0.0; }
  double time_limit() const { return time_limit_; }

  // Calls the function lying below `num_args` arguments on the stack in
  // protected mode (bounded by the instruction limit), with TracebackHandler
  // as message handler. On success
  // leaves `num_results` results (LUA_MULTRET: all) and returns true. On
  // failure removes the function and arguments, stores the message (with a
  // traceback) in *error and returns false.
  bool Call(int num_args, int num_results, std::string* error);

  // Loads `code` as a text chunk named `chunk_name` ("@file.lua" gives
  // messages "file.lua:12: ...", "=name" gives "name:12: ...") and runs it
  // with no results. Returns false with the message in *error on a syntax or
  // run-time error, or when compiling it could take too long
  // (CompileCostProblem in scripting/lua_guards.h).
  bool Run(std::string_view code, const std::string& chunk_name, std::string* error);

  // The text of the error value on top of the stack after a failed call that
  // returned `status`; "not enough memory" gets the limit added. Does not pop.
  std::string ErrorText(int status) const;

  // Message handler for lua_pcall, as in lua.c: turns a non-string error
  // object into text (its __tostring, or "(error object is a T value)") and
  // appends a stack traceback.
  static int TracebackHandler(lua_State* L);

  // True while the current bounded call is past a limit (its error is being
  // raised): Lua code that would run now, as a message handler does inside
  // the hook that raises it, runs with hooks off and must not run at all.
  static bool LimitPassed(lua_State* L);

  // Raises `text` (with the calling line's position) as a limit's error:
  // inside a bounded call, every further instruction raises it again, so a
  // guard's refusal cannot be caught and ignored. For the guards of
  // scripting/lua_guards.h; never returns.
  static int RaiseLimit(lua_State* L, const char* text);

  // Looks at the clock after C work the count cannot see (a long search, a
  // full garbage collection): past the time limit, the hook runs at the next
  // instruction. Cheap; does nothing outside a bounded call.
  static void CheckTimeSoon(lua_State* L);

  // Arms the count hook from inside a call that runs without it (see
  // StraightLineCall), from the point where that call reached a value through
  // which Lua code could run. Inside a bounded call it does nothing.
  static void BoundFromHere(lua_State* L);

  // Names defined by the sandbox for expressions (sin, ln, pi, ...).
  static bool IsBuiltinName(std::string_view name);
  static std::vector<std::string> BuiltinNames();

  // True when the value at `index` is one of the sandbox's own functions of
  // numbers (the functions named by BuiltinNames, as set up): whatever its
  // arguments, it runs no Lua code and reaches no metatable. A global of the
  // same name that a script rebound is not.
  static bool IsPureFunction(lua_State* L, int index);

 private:
  struct Memory {
    std::size_t used = 0;
    std::size_t limit = std::size_t(256) << 20;
    LuaState* owner = nullptr;
  };
  // Blocks this large make the allocator look at the clock (HurryTimeCheck).
  static constexpr std::size_t kLargeBlock = std::size_t(64) << 10;
  // Past the time limit, the hook is made to run at the next instruction: a
  // loop of costly C calls (each one instruction, each allocating) would
  // otherwise overrun the limit by kCheckInterval of them.
  void HurryTimeCheck();
  static void* Allocate(void* ud, void* ptr, std::size_t old_size, std::size_t new_size);

  friend class BoundedCall;
  friend class StraightLineCall;
  static void InstructionHook(lua_State* L, lua_Debug* ar);

  // What the hook of the current bounded call has seen.
  enum class Exceeded { kNone, kInstructions, kTime, kRefused };
  struct CallBudget {
    long instructions = 0;  // counted so far, in steps of the hook's interval
    double start = 0.0;     // steady clock, s
    int interval = kCheckInterval;
    Exceeded exceeded = Exceeded::kNone;
    bool armed_midway = false;  // by BoundFromHere, in a StraightLineCall
  };
  // Arms the hook for a new bounded call (the hook must not be set).
  void Arm();

  Memory memory_;
  CallBudget call_;
  int run_time_code_ = 0;
  int stateful_code_ = 0;
  std::mutex claim_mutex_;  // guards the two below (claims are made once per run)
  std::thread::id claim_thread_;
  int claims_ = 0;
  char refusal_[400] = "";  // a guard's message (kRefused), raised again by the hook
  long instruction_limit_ = 0;
  double time_limit_ = 0.0;
  bool unsafe_ = false;
  lua_State* L_ = nullptr;
};

// Bounds one protected call from C++ by the instruction limit: arms the count
// hook afresh on construction (so the count is per call) and removes it on
// destruction. Wrap every direct lua_pcall in one. Inside a call already
// bounded (Lua called C++ which calls Lua again) it does nothing, so code
// cannot reset its own count that way. The unsafe debug library can, by
// design, change the hook.
class BoundedCall {
 public:
  explicit BoundedCall(LuaState& lua);
  ~BoundedCall();
  BoundedCall(const BoundedCall&) = delete;
  BoundedCall& operator=(const BoundedCall&) = delete;

 private:
  lua_State* L_;
  bool armed_ = false;
};

// Runs straight-line code (which cannot loop) without the count hook, so a
// call costs no hook. Should that code reach a value through which Lua code
// could run (a table of a script, with a metatable), it calls
// LuaState::BoundFromHere, and the rest of the call is bounded; the
// destructor removes the hook again.
class StraightLineCall {
 public:
  explicit StraightLineCall(LuaState& lua) : lua_(lua) {}
  ~StraightLineCall();
  StraightLineCall(const StraightLineCall&) = delete;
  StraightLineCall& operator=(const StraightLineCall&) = delete;

  // True once the call was bounded from midway: the code is not safe to run
  // unbounded, and its next calls should be bounded from the start.
  bool bounded_midway() const { return lua_.call_.armed_midway; }

 private:
  LuaState& lua_;
};

}  // namespace mechflow::scripting
