#include "scripting/lua_block.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <sstream>

#include <lua.hpp>

#include "mech/errors.h"
#include "scripting/identifier_bindings.h"
#include "scripting/identifiers.h"
#include "scripting/lua_guards.h"
#include "scripting/lua_lexer.h"
#include "scripting/lua_state.h"

namespace mechflow::scripting {
namespace {

// The code with identifier names in their canonical lower case, and the
// identifiers and sandbox functions it names (each once, in order of use).
// Names after '.', ':' or '::' are fields, methods or labels, not variables.
//
// `may_loop` is false only for straight-line code, which ends after a number
// of VM instructions bounded by its length and so may run without the
// instruction-count hook (bench_lua: the hook costs about 40 ns of a 116 ns
// call). Straight-line means: no while, for, repeat or goto; `function` only
// to define outputs and derivatives (so no other Lua function exists for a
// call or a metamethod to reach); every call made to a sandbox function by
// its plain name (so no recursion, no method call, no call of a global a
// script defined); and every sandbox function named only to be called (so
// none can be rebound to a Lua function).
// Anything else is bounded, as before. Values can still run Lua code
// through metamethods (a table of the control script whose __index loops;
// "no other Lua function exists" holds only for the code's own): so
// straight-line code reads globals through ReadGlobal, and its functions'
// upvalues must be safe (SafeUpvalue).
struct CodeScan {
  std::string rewritten;
  std::vector<std::string> identifiers;
  std::vector<std::string> builtins;
  bool may_loop = false;
};

// True when a call's argument list may start at `i`: '(', '{' or a string.
bool CallFollows(const std::string& s, std::size_t i) {
  while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
  if (i >= s.size()) return false;
  return s[i] == '(' || s[i] == '{' || s[i] == '"' || s[i] == '\'' || LongBracketOpen(s, i) > 0;
}

CodeScan ScanCode(const std::string& code, const IdentifierTable& ids) {
  CodeScan scan;
  std::string previous;       // the previous token if punctuation
  std::string previous_word;  // the previous token if a name or keyword
  for (std::size_t i = 0, end = 0; i < code.size(); i = end) {
    const LuaToken kind = NextLuaToken(code, i, &end);
    if (kind == LuaToken::kSpace || kind == LuaToken::kComment) {
      scan.rewritten.append(code, i, end - i);
      continue;
    }
    if (kind == LuaToken::kName) {
      std::string name = code.substr(i, end - i);
      const bool field = previous == "." || previous == ":" || previous == "::";
      const bool defined = previous_word == "function";
      if (!IsLuaName(name)) {  // a keyword
        if (name == "while" || name == "for" || name == "repeat" || name == "goto") scan.may_loop = true;
      } else if (field) {
        if (CallFollows(code, end)) scan.may_loop = true;  // a method or a library function
      } else {
        const bool builtin = LuaState::IsBuiltinName(name) && !ids.Has(name);
        const bool callable = builtin && name != "pi";
        const bool call = !defined && CallFollows(code, end);
        if (defined && name != "outputs" && name != "derivatives") scan.may_loop = true;
        if (call && !callable) scan.may_loop = true;
        // a sandbox function named other than in a call may be rebound to a Lua one
        if (callable && !call) scan.may_loop = true;
        if (ids.Has(name)) {
          name = ToLower(name);
          if (std::find(scan.identifiers.begin(), scan.identifiers.end(), name) == scan.identifiers.end())
            scan.identifiers.push_back(name);
        } else if (builtin && std::find(scan.builtins.begin(), scan.builtins.end(), name) == scan.builtins.end()) {
          scan.builtins.push_back(name);
        }
      }
      scan.rewritten += name;
      previous.clear();
      previous_word = name;
      continue;
    }
    previous.clear();
    if (kind == LuaToken::kPunctuation) {
      previous = code.substr(i, end - i);
      // an anonymous function, or a call of what an expression gave
      const char c = code[i];
      if (previous_word == "function" || ((c == ')' || c == ']') && CallFollows(code, end))) scan.may_loop = true;
    }
    previous_word.clear();
    scan.rewritten.append(code, i, end - i);
  }
  return scan;
}

// __index of a straight-line block's environment (upvalue 1: the globals,
// upvalue 2: set true once a read found an unsafe value). Reads a global
// raw, as the table __index it replaces did (_G's metatable is protected
// and empty). A value that can carry a metatable or run code -- a table,
// function or userdata of a script -- could reach Lua code through a
// metamethod, which straight-line code must not run unbounded: the call is
// bounded from here on (LuaState::BoundFromHere), and the block knows to
// bound every later call.
// Called by Lua (may long-jump): owns no C++ object with a destructor.
int ReadGlobal(lua_State* L) {
  lua_pushvalue(L, 2);
  const int type = lua_rawget(L, lua_upvalueindex(1));
  if (type == LUA_TFUNCTION && LuaState::IsPureFunction(L, -1)) return 1;  // sin, sqrt, ...
  if (type == LUA_TTABLE || type == LUA_TFUNCTION || type == LUA_TUSERDATA || type == LUA_TTHREAD) {
    lua_pushboolean(L, 1);
    lua_replace(L, lua_upvalueindex(2));
    LuaState::BoundFromHere(L);
  }
  return 1;
}

// True when the value at `index`, an upvalue of a straight-line function,
// runs no Lua code however the code uses it: a number, string, boolean or
// nil, one of the sandbox's functions of numbers, the block's environment
// (at `env`), or a table without a metatable (one made by the code itself).
bool SafeUpvalue(lua_State* L, int index, int env) {
  switch (lua_type(L, index)) {
    case LUA_TNIL:
    case LUA_TBOOLEAN:
    case LUA_TNUMBER:
    case LUA_TSTRING:
      return true;
    case LUA_TFUNCTION:
      return LuaState::IsPureFunction(L, index);
    case LUA_TTABLE:
      if (lua_rawequal(L, index, env)) return true;
      if (!lua_getmetatable(L, index)) return true;
      lua_pop(L, 1);
      return false;
    default:
      return false;
  }
}

struct Port {
  std::string name;
  int width = 1;
};

// "u v:3" -> ports; names must be Lua names, unique within `what`.
std::vector<Port> ParsePorts(const std::string& text, const std::string& what) {
  std::istringstream in(text);
  std::vector<Port> ports;
  for (std::string item; in >> item;) {
    Port port{item, 1};
    if (const std::size_t colon = item.find(':'); colon != std::string::npos) {
      port.name = item.substr(0, colon);
      const std::string width = item.substr(colon + 1);
      double w = 0;
      if (!ParseNumber(width, &w) || w < 1 || w != std::floor(w) || w > 1000)
        throw InputError(what + " '" + item + "': the width after ':' must be a whole number from 1 to 1000");
      port.width = static_cast<int>(w);
    }
    if (!IsLuaName(port.name))
      throw InputError(what + " name '" + port.name + "' must be a Lua name (letters, digits, '_'; not a keyword)");
    for (const auto& p : ports)
      if (p.name == port.name) throw InputError(what + " name '" + port.name + "' is given twice");
    ports.push_back(port);
  }
  return ports;
}

int TotalWidth(const std::vector<Port>& ports) {
  int n = 0;
  for (const auto& p : ports) n += p.width;
  return n;
}

// Where the code comes from, for the chunk name and line shift.
struct Code {
  std::string text;
  std::string chunk_name;  // "@file"
  int first_line = 1;      // file line of the text's first character
};

class LuaBlock : public blocks::Block {
 public:
  LuaBlock(const std::string& name, const Code& code, const std::vector<Port>& inputs,
           const std::vector<Port>& outputs, const std::vector<std::string>& states, std::vector<double> initial,
           const std::string& feedthrough, LuaState& lua, const IdentifierTable& ids)
      : Block("lua", name), lua_(lua), initial_(std::move(initial)) {
    for (const auto& p : inputs) DeclareInputPort(p.name, p.width);
    for (const auto& p : outputs) DeclareOutputPort(p.name, p.width);
    for (const auto& s : states) DeclareContinuousStates(1, s);
    DeclareFeedthrough(feedthrough, inputs, outputs);
    num_input_values_ = TotalWidth(inputs);
    num_output_values_ = TotalWidth(outputs);
    num_args_ = 1 + static_cast<int>(states.size()) + num_input_values_;
    lua_.NoteRunTimeCode();  // called during runs: they must claim the state
    lua_.NoteCodeThatMayKeepState();  // its upvalues and globals
    Compile(code, ids, !states.empty());
  }

  ~LuaBlock() override {
    lua_State* L = lua_.get();
    for (const int ref : {outputs_ref_, derivatives_ref_, binder_ref_})
      if (ref >= 0) luaL_unref(L, LUA_REGISTRYINDEX, ref);
  }

 protected:
  // The run's arguments and the last call of `outputs`, sized once.
  struct Scratch final : blocks::BlockScratch {
    Scratch(int num_args, int num_outputs)
        : args(num_args, 0.0), cached_args(num_args, 0.0), cached_outputs(num_outputs, 0.0) {}
    std::vector<double> args;  // (t, states, inputs)
    std::vector<double> cached_args;
    std::vector<double> cached_outputs;
    std::uint64_t cached_evaluation = 0;
    bool has_cache = false;
  };

  std::unique_ptr<blocks::BlockScratch> MakeScratch() const override {
    return std::make_unique<Scratch>(num_args_, num_output_values_);
  }

  void DoInitialize(const blocks::BlockContext& ctx) const override {
    std::copy(initial_.begin(), initial_.end(), ctx.state().begin());
    ctx.scratch<Scratch>().has_cache = false;
  }

  void DoCalcOutput(int port, const blocks::BlockContext& ctx) const override {
    if (outputs_ref_ < 0) {  // the outputs are the states
      const std::span<double> out = ctx.output(port);
      std::copy_n(ctx.state().begin() + output_first_[port], out.size(), out.begin());
      return;
    }
    Scratch& s = ctx.scratch<Scratch>();
    GatherArguments(ctx, s);
    // the other ports' call may already hold this port's values
    const bool cached = s.has_cache && num_outputs() > 1 && s.cached_evaluation == ctx.evaluation() &&
                        std::equal(s.args.begin(), s.args.end(), s.cached_args.begin());
    if (!cached) {
      Call(s, outputs_ref_, "outputs", num_output_values_, s.cached_outputs.data());
      s.cached_args = s.args;  // same size: copies, no allocation
      s.cached_evaluation = ctx.evaluation();
      s.has_cache = true;
    }
    const std::span<double> out = ctx.output(port);
    std::copy_n(s.cached_outputs.begin() + output_first_[port], out.size(), out.begin());
  }

  void DoCalcDerivatives(const blocks::BlockContext& ctx) const override {
    if (num_states() == 0) return;
    Scratch& s = ctx.scratch<Scratch>();
    GatherArguments(ctx, s);
    Call(s, derivatives_ref_, "derivatives", num_states(), ctx.derivative().data());
  }

 private:
  // "y:u,v z:w" or "none"; absent (empty): the default, every pair
  void DeclareFeedthrough(const std::string& text, const std::vector<Port>& inputs,
                          const std::vector<Port>& outputs) {
    output_first_.clear();
    for (int o = 0, first = 0; o < num_outputs(); ++o) {
      output_first_.push_back(first);
      first += outputs[o].width;
    }
    std::istringstream in(text);
    std::vector<std::string> items;
    for (std::string item; in >> item;) items.push_back(item);
    if (items.empty()) return;
    if (items.size() == 1 && items[0] == "none") {
      DeclareNoFeedthrough();
      return;
    }
    std::vector<std::vector<bool>> reads(num_outputs(), std::vector<bool>(num_inputs(), false));
    std::vector<std::string> listed;
    for (const auto& item : items) {
      const std::size_t colon = item.find(':');
      const std::string out_name = item.substr(0, colon);
      const int out = FindOutput(out_name);
      if (colon == std::string::npos || out < 0)
        throw InputError("feedthrough '" + item + "': expected output:input[,input...] with an output of " +
                         Names(outputs) + " (or feedthrough=\"none\")");
      if (std::find(listed.begin(), listed.end(), out_name) != listed.end())
        throw InputError("feedthrough lists the output '" + out_name + "' twice");
      listed.push_back(out_name);
      std::istringstream list(item.substr(colon + 1));
      int count = 0;
      for (std::string in_name; std::getline(list, in_name, ',');) {
        const int in = FindInput(in_name);
        if (in < 0)
          throw InputError("feedthrough '" + item + "': '" + in_name + "' is not an input" +
                           (inputs.empty() ? " (the block has none)" : "; inputs: " + Names(inputs)));
        reads[out][in] = true;
        ++count;
      }
      if (count == 0) throw InputError("feedthrough '" + item + "' names no input after ':'");
    }
    for (int out = 0; out < num_outputs(); ++out)
      for (int in = 0; in < num_inputs(); ++in)
        if (!reads[out][in]) SetFeedthrough(in, out, false);
  }

  static std::string Names(const std::vector<Port>& ports) {
    std::string out;
    for (const auto& p : ports) out += (out.empty() ? "" : ", ") + p.name;
    return out.empty() ? "(none)" : out;
  }

  // Runs the code once in an environment of its own and keeps references to
  // its functions and to a closure over the identifier upvalues.
  void Compile(const Code& code, const IdentifierTable& ids, bool has_states) {
    if (const std::string problem = CompileCostProblem(code.text); !problem.empty())
      throw InputError("the Lua code cannot be compiled: " + problem);
    const CodeScan scan = ScanCode(code.text, ids);
    // line 1: the upvalues, then blank lines up to the code's line in its file
    std::string chunk = "local __mechflow_binder";
    for (const auto& name : scan.identifiers) chunk += ", " + name;
    chunk += " = ...; ";
    if (!scan.identifiers.empty()) {
      chunk += "__mechflow_binder[1] = function() return ";
      for (std::size_t i = 0; i < scan.identifiers.size(); ++i) chunk += (i ? ", " : "") + scan.identifiers[i];
      chunk += " end; ";
    }
    chunk += "__mechflow_binder = nil; ";
    if (!scan.builtins.empty()) {
      chunk += "local ";
      for (std::size_t i = 0; i < scan.builtins.size(); ++i) chunk += (i ? ", " : "") + scan.builtins[i];
      chunk += " = ";
      for (std::size_t i = 0; i < scan.builtins.size(); ++i) chunk += (i ? ", " : "") + scan.builtins[i];
      chunk += "; ";
    }
    chunk += std::string(std::max(code.first_line - 1, 0), '\n') + scan.rewritten;

    lua_State* L = lua_.get();
    const int top = lua_gettop(L);
    const auto fail = [&](const std::string& what) {
      lua_settop(L, top);
      throw InputError(what);
    };
    if (!lua_checkstack(L, static_cast<int>(scan.identifiers.size()) + 8)) fail("the code names too many identifiers");
    int status = luaL_loadbufferx(L, chunk.data(), chunk.size(), code.chunk_name.c_str(), "t");
    if (status != LUA_OK) fail("the Lua code does not compile: " + lua_.ErrorText(status));
    // the environment: a table of its own whose reads fall through to the
    // globals; straight-line code reads them through ReadGlobal
    lua_newtable(L);
    lua_newtable(L);
    lua_pushglobaltable(L);
    if (!scan.may_loop) {
      lua_pushboolean(L, 0);
      lua_pushcclosure(L, &ReadGlobal, 2);
    }
    lua_setfield(L, -2, "__index");
    lua_setmetatable(L, -2);
    lua_pushvalue(L, -1);
    if (!lua_setupvalue(L, top + 1, 1)) fail("internal error: the chunk has no _ENV");
    // stack: chunk, env -> env, box, chunk, box, identifier values
    lua_insert(L, top + 1);
    lua_newtable(L);  // the binder's box: the chunk stores its closure in [1]
    lua_insert(L, top + 2);
    lua_pushvalue(L, top + 2);
    for (const auto& name : scan.identifiers) lua_pushnumber(L, ids.Value(name));
    std::string error;
    if (!lua_.Call(1 + static_cast<int>(scan.identifiers.size()), 0, &error))
      fail("the Lua code fails when it runs at load: " + error);

    // stack: env, box
    outputs_ref_ = TakeFunction(L, "outputs", top + 1, !has_states,
                                "(t, states..., inputs...) returning the outputs");
    derivatives_ref_ = TakeFunction(L, "derivatives", top + 1, has_states,
                                    "(t, states..., inputs...) returning one derivative per state");
    if (!has_states && derivatives_ref_ >= 0) {
      luaL_unref(L, LUA_REGISTRYINDEX, derivatives_ref_);
      fail("the code defines 'derivatives' but the block declares no states (add states=\"...\" and initial=\"...\")");
    }
    if (outputs_ref_ < 0) {
      // without `outputs` the outputs are the states: no call, no feedthrough
      if (num_output_values_ != num_states())
        fail("the code defines no function 'outputs', so the outputs are the states, but the outputs have " +
             std::to_string(num_output_values_) + " value(s) for " + std::to_string(num_states()) +
             " state(s); define outputs(t, states..., inputs...)");
      DeclareNoFeedthrough();
    }
    // straight-line code may skip the instruction count, unless it read a
    // global through which Lua code could run, or a value it keeps could run
    // some (a sandbox name bound to another function or to a table)
    bounded_ = scan.may_loop;
    if (!bounded_) {
      lua_getmetatable(L, top + 1);
      lua_getfield(L, -1, "__index");
      lua_getupvalue(L, -1, 2);
      bounded_ = lua_toboolean(L, -1);
      lua_pop(L, 3);
    }
    for (const int ref : {outputs_ref_, derivatives_ref_}) {
      if (ref < 0) continue;
      lua_rawgeti(L, LUA_REGISTRYINDEX, ref);
      for (int i = 1; lua_getupvalue(L, -1, i); ++i) {
        if (!SafeUpvalue(L, -1, top + 1)) bounded_ = true;
        lua_pop(L, 1);
      }
      lua_pop(L, 1);
    }
    if (lua_rawgeti(L, top + 2, 1) == LUA_TFUNCTION) {
      BindIdentifiers(L, -1);
      binder_ref_ = luaL_ref(L, LUA_REGISTRYINDEX);  // keeps the weakly bound closure alive
    }
    lua_settop(L, top);
  }

  // A registry reference to the function `name` of the environment at
  // `env`, or -1 when absent and not `required`.
  int TakeFunction(lua_State* L, const char* name, int env, bool required, const std::string& signature) {
    const int type = lua_getfield(L, env, name);
    if (type == LUA_TFUNCTION) return luaL_ref(L, LUA_REGISTRYINDEX);
    const std::string found = type == LUA_TNIL ? "" : std::string(" (it is a ") + lua_typename(L, type) + ")";
    lua_pop(L, 1);
    if (required) {
      lua_settop(L, env - 1);
      throw InputError("the Lua code defines no function '" + std::string(name) + "'" + found + "; expected " +
                       name + signature);
    }
    if (type != LUA_TNIL) {
      lua_settop(L, env - 1);
      throw InputError("'" + std::string(name) + "' is not a function" + found);
    }
    return -1;
  }

  // s.args = (t, states, inputs)
  void GatherArguments(const blocks::BlockContext& ctx, Scratch& s) const {
    double* a = s.args.data();
    *a++ = ctx.time();
    for (const double x : ctx.state()) *a++ = x;
    for (int i = 0; i < num_inputs(); ++i)
      for (const double u : ctx.input(i)) *a++ = u;
  }

  // Calls the function at `ref` with s.args and writes its `count` results.
  void Call(const Scratch& s, int ref, const char* function, int count, double* out) const {
    lua_State* L = lua_.get();
    const int top = lua_gettop(L);
    const int n = static_cast<int>(s.args.size());
    if (!lua_checkstack(L, n + 2)) throw SimulationError("block '" + name() + "': Lua stack overflow");
    lua_pushcfunction(L, &LuaState::TracebackHandler);
    lua_rawgeti(L, LUA_REGISTRYINDEX, ref);
    for (const double a : s.args) lua_pushnumber(L, a);
    int status;
    if (bounded_) {
      BoundedCall bounded(lua_);
      status = lua_pcall(L, n, LUA_MULTRET, top + 1);
    } else {
      StraightLineCall straight(lua_);
      status = lua_pcall(L, n, LUA_MULTRET, top + 1);
      if (straight.bounded_midway()) bounded_ = true;
    }
    if (status != LUA_OK) {
      const std::string message = lua_.ErrorText(status);
      lua_settop(L, top);
      throw SimulationError(Where(s, function) + ": " + message);
    }
    const int returned = lua_gettop(L) - top - 1;
    if (returned != count) {
      lua_settop(L, top);
      throw SimulationError(Where(s, function) + ": returned " + std::to_string(returned) + " value" +
                            (returned == 1 ? "" : "s") + ", expected " + std::to_string(count) + " (" +
                            (function[0] == 'o' ? "one per output value" : "one per state") + ")");
    }
    for (int i = 0; i < count; ++i) {
      int is_number = 0;
      const double v = lua_tonumberx(L, top + 2 + i, &is_number);
      if (!is_number || !std::isfinite(v)) {
        const std::string got = is_number ? std::to_string(v) : std::string("a ") + luaL_typename(L, top + 2 + i);
        lua_settop(L, top);
        throw SimulationError(Where(s, function) + ": value " + std::to_string(i + 1) + " is " + got +
                              ", not a finite number");
      }
      out[i] = v;
    }
    lua_settop(L, top);
  }

  // "block 'f': Lua function outputs at t = 0.5, x1 = 2, u = 1"
  std::string Where(const Scratch& s, const char* function) const {
    std::string out = "block '" + name() + "': Lua function " + function + " at t = ";
    char value[32];
    std::snprintf(value, sizeof value, "%.9g", s.args[0]);
    out += value;
    int a = 1;
    for (int x = 0; x < num_states(); ++x, ++a) {
      std::snprintf(value, sizeof value, "%.6g", s.args[a]);
      out += ", " + state_name(x) + " = " + value;
    }
    for (int i = 0; i < num_inputs(); ++i)
      for (int k = 0; k < input_port(i).width; ++k, ++a) {
        std::snprintf(value, sizeof value, "%.6g", s.args[a]);
        out += ", " + input_port(i).name + (input_port(i).width > 1 ? "[" + std::to_string(k) + "]" : "") +
               " = " + value;
      }
    return out;
  }

  LuaState& lua_;
  std::vector<double> initial_;
  int num_input_values_ = 0;
  int num_output_values_ = 0;
  std::vector<int> output_first_;  // per output port: its first value among the returned ones
  int outputs_ref_ = -1;
  int derivatives_ref_ = -1;
  int binder_ref_ = -1;
  int num_args_ = 0;  // 1 + states + input values
  // false for straight-line code (CodeScan::may_loop) that reaches no value
  // through which Lua code could run; set when a call finds one. A fact about
  // the code in the diagram's one Lua state, not about a run: it stays set
  // for later runs (which share that state and so never run at once).
  mutable bool bounded_ = true;
};

}  // namespace

void RegisterLuaBlock(blocks::BlockRegistry* registry, LuaState* lua, const IdentifierTable* identifiers) {
  blocks::BlockType type;
  type.name = "lua";
  type.doc = "outputs and state derivatives computed by Lua functions";
  type.takes_text = true;
  type.params = {
      {"inputs", blocks::ParamKind::kText, false, "", "input ports: names, each optionally ':width' (\"u v:3\")"},
      {"outputs", blocks::ParamKind::kText, false, "y", "output ports: names, each optionally ':width'"},
      {"states", blocks::ParamKind::kText, false, "", "continuous state names"},
      {"initial", blocks::ParamKind::kNumbers, false, "", "initial state values, one per state (default 0)"},
      {"feedthrough", blocks::ParamKind::kText, false, "",
       "\"y:u,v z:w\": inputs each output reads at the same instant; \"none\"; default: all"},
      {"src", blocks::ParamKind::kPath, false, "", "Lua file with the code (else the element's text)"},
  };
  type.create = [lua, identifiers](const std::string& name, const blocks::BlockParams& p) {
    const std::vector<Port> inputs = ParsePorts(p.Has("inputs") ? p.Text("inputs") : "", "input");
    const std::vector<Port> outputs = ParsePorts(p.Has("outputs") ? p.Text("outputs") : "y", "output");
    if (outputs.empty()) throw InputError("a lua block needs at least one output (outputs=\"y\")");
    std::vector<std::string> states;
    for (const auto& s : ParsePorts(p.Has("states") ? p.Text("states") : "", "state")) {
      if (s.width != 1) throw InputError("state '" + s.name + "': states are scalars (no ':width')");
      states.push_back(s.name);
    }
    std::vector<double> initial(states.size(), 0.0);
    if (p.Has("initial")) {
      initial = p.Numbers("initial");
      if (initial.size() != states.size())
        throw InputError("initial has " + std::to_string(initial.size()) + " value(s) for " +
                         std::to_string(states.size()) + " state(s)");
    }
    const bool has_text = p.Has("#text");
    Code code;
    if (p.Has("src")) {
      if (has_text) throw InputError("the code is given twice: src=\"...\" and as the element's text; keep one");
      code.text = p.FileText("src");  // read by the loader, inside the diagram's folder tree
      code.chunk_name = "@" + p.Text("src");
    } else if (has_text) {
      code.text = p.Text("#text");
      code.chunk_name = "@" + (p.Has("#text_file") ? p.Text("#text_file") : std::string("lua block"));
      code.first_line = p.Has("#text_line") ? static_cast<int>(p.Number("#text_line")) : 1;
    } else {
      throw InputError("no Lua code: write it as the element's text or give src=\"file.lua\"");
    }
    return std::make_unique<LuaBlock>(name, code, inputs, outputs, states, std::move(initial),
                                      p.Has("feedthrough") ? p.Text("feedthrough") : "", *lua, *identifiers);
  };
  registry->Add(std::move(type));
}

}  // namespace mechflow::scripting
