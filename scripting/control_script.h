#pragma once
// ControlScript: a diagram's Lua control script, acting on its runs (what
// compiled control files did in the old workflow).
//
// The script is a Lua chunk run once when the diagram is loaded; it may
// define the global functions
//   init(sim)    at t_start, before the first row is recorded,
//   step(sim)    at every later output time, before its row is recorded,
//   finish(sim)  after the last row of a run that did not fail,
// and, from any of them, register sampled callbacks with
//   sim:every(period, fn [, offset])   fn(sim) at t0 + offset + k period,
//                                      k = 0, 1, ...; t0 is the time of the call;
//                                      the integrator stops at exactly those times.
// The script reads identifiers by name (any case), as Lua blocks do: `Ts` is
// the identifier's current value, after any sim:set (RunControlScript). It
// cannot assign one (`Ts = 1` is refused at load; sim:set changes it), but
// a local of that name may hide it.
// The `sim` object:
//   sim.t               current time [s]
//   sim:get(name [, i]) a signal "block.port" (i: 1-based element of a vector
//                       port), an identifier, or an output port name that
//                       only one block has (a sensor name such as "phi")
//   sim:set(name, v)    sets an identifier defined by a number; identifiers
//                       defined from it are evaluated again, compiled
//                       expressions, Lua blocks and identifier blocks follow,
//                       and the integrator is re-initialised. An identifier
//                       whose value was built into the model at load (a block
//                       parameter, a mass, a time function) cannot change:
//                       that is an error naming where it is used.
//   sim:stop(reason)    ends the run after this callback (successfully)
//   sim:log(...)        writes "t = <t>: ..." to stderr
// Every callback runs under the Lua state's instruction limit (a runaway
// loop ends the run within a fraction of a second); an error ends the run
// (exit 1, results so far kept) with the callback's name, the time, the
// script's file:line and a traceback.
//
// Every change made by sim:set is kept (changes()), so a run can show what the
// script did to the model.

#include <memory>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "blocks/framework/diagram.h"
#include "blocks/solver/run_control.h"

struct lua_State;

namespace mechflow::scripting {

class CompiledExpression;
class IdentifierTable;
class LuaState;

// Runs a control script's code once in `lua`, as the loader does before
// making its ControlScript: identifiers the code names are upvalues bound to
// the identifier table (IdentifiersAsUpvalues in identifier_bindings.h), so
// they read their current values and cost no name look-up. Returns false
// with the message in *error on a syntax or run-time error.
bool RunControlScript(LuaState& lua, const IdentifierTable& identifiers, const std::string& code,
                      const std::string& chunk_name, std::string* error);

class ControlScript final : public blocks::RunControl {
 public:
  struct Change {
    double time = 0.0;
    int identifier = 0;  // index in the identifier table
    double value = 0.0;
  };

  // The script must already have run in `lua` (so its functions exist).
  // `script_name` names it in messages. Throws InputError when init, step or
  // finish is defined as something other than a function.
  ControlScript(LuaState& lua, IdentifierTable& identifiers, const blocks::Diagram& diagram,
                std::string script_name);
  ~ControlScript() override;
  ControlScript(const ControlScript&) = delete;
  ControlScript& operator=(const ControlScript&) = delete;

  void Start(blocks::ControlPoint& point) override;
  void Output(blocks::ControlPoint& point) override;
  double NextTimer() const override;
  void Timer(blocks::ControlPoint& point) override;
  void Finish(blocks::ControlPoint& point) override;

  const std::string& name() const { return name_; }
  // Which of init, step and finish the script defines.
  std::vector<std::string> functions() const;
  const std::vector<Change>& changes() const { return changes_; }
  long callbacks() const { return callbacks_; }  // Lua callbacks run in the last run

 private:
  struct Sampled {
    double start = 0.0, period = 0.0;
    long next = 0;  // the next call is at start + next * period
    int function_ref = -1;
    double when() const { return start + next * period; }
  };
  // What sim:get(name) reads, resolved on first use.
  struct Target {
    bool is_identifier = false;
    int index = 0;  // identifier index or signal offset
    int width = 1;
    std::string fed_by;  // an identifier a signal feeds into a mechanism: "m.Ffr <- f.y"; read as that signal
  };

  // The methods of `sim`, called by Lua. They may raise Lua errors, so they
  // hold no C++ object with a destructor; the work is done by the Do*
  // members, which report failures in error_.
  static int Every(lua_State* L);
  static int Get(lua_State* L);
  static int Set(lua_State* L);
  static int StopRun(lua_State* L);
  static int Log(lua_State* L);
  static ControlScript& Self(lua_State* L);
  static int RaiseError(lua_State* L);  // error_ with the calling line's position

  bool DoGet(const char* name, long long element, double* value);
  bool DoSet(const char* name, double value);
  bool Resolve(const std::string& name, Target* target);
  // Calls the function referenced by `ref` with `sim`; `what` names it in messages.
  void Call(int ref, const char* what, blocks::ControlPoint& point);

  LuaState& lua_;
  IdentifierTable& identifiers_;
  const blocks::Diagram& diagram_;
  std::string name_;
  int init_ref_ = -1, step_ref_ = -1, finish_ref_ = -1;
  int sim_ref_ = -1;
  std::vector<double> loaded_values_;     // identifier values at load
  // (index, compiled definition) of every identifier defined by an expression
  std::vector<std::pair<int, std::unique_ptr<CompiledExpression>>> derived_;
  std::vector<double> before_;            // scratch: values before a set
  std::vector<std::string> changed_;      // scratch: names a set changed
  std::vector<std::pair<int, int>> identifier_blocks_;  // (identifier, discrete offset)
  std::unordered_map<std::string, Target> targets_;
  std::vector<Sampled> timers_;
  std::vector<Change> changes_;
  long callbacks_ = 0;
  blocks::ControlPoint* point_ = nullptr;  // during a callback
  std::string error_;
};

}  // namespace mechflow::scripting
