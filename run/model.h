#pragma once
// run::Model: a diagram loaded once, run as often as wanted.
//
//   run::Model model("damping_ratio.xml");          // read, checked, built
//   model.Set("beta", 0.1);                         // as --set beta=0.1
//   run::MemorySink rows;
//   const run::RunResult r = model.Run({}, &rows);  // rows.columns()[c]
//
// The file is read and parsed once; the parsed description is kept. A run
// needs a diagram built from it (blocks, Lua state, identifiers, solver
// settings): the diagram built by the load serves the first run. A later run
// with the same settings runs on it again when no Lua code that could keep
// state runs during a run (no control script, no Lua block, no expression
// calling more than pure functions of numbers): a run keeps its states,
// signals and caches in its own context, so nothing of one run reaches the
// next. Otherwise, and when Set has changed a value or the run overrides
// other solver settings, the run builds the diagram again from the kept
// description (diagrams::LoadDiagramDescription), as a fresh load with the
// same --set would, so it gives the same numbers bit for bit: Lua code may
// keep state between calls (a local of a script's chunk, a Lua block's
// upvalue), which a second run would start from, and identifier values
// cannot change in place
// (block parameters are evaluated into numbers when the diagram is built;
// only Lua-bound reads follow sim:set).
// Cost, measured (Release): a load (read, parse, build) 0.7 to 5 ms, a
// rebuild 0.15 to 0.7 ms (elast_friction, variant Free: about 0.6 ms, a
// quarter of its 2.5 ms run), the run 10 to 90 ms for the longer examples
// (damping_ratio, pendulum_pd_control, fidget, tension_mechanism,
// cart_pendulum_friction).
//
// Errors: InputError for bad input (a name Set does not know, a value the
// model refuses when it is rebuilt), as the command line reports them.

#include <csignal>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "blocks/solver/simulator.h"
#include "diagrams/loader.h"
#include "run/columns.h"

namespace mechflow::run {

// How a model is loaded: variants, --set values, solver and output
// overrides, the sandbox (unsafe_lua, allow_read).
using LoadOptions = diagrams::LoadOptions;

// One identifier of the model as it stands (after variants and Set).
struct Identifier {
  std::string name;     // as the diagram spells it
  double value = 0.0;   // SI
  std::string unit;     // the unit its definition is written in ("" none)
  std::string comment;
  bool derived = false;  // defined by an expression of other identifiers
};

// What a run is to do besides what the diagram says.
struct RunOptions {
  std::optional<double> t_end, rtol, atol, interval;  // as --t-end, --rtol, --atol, --interval
  // Signals to log ("block.port", "block.port[i]"); none given: the diagram's
  // <log>s and recorders (with their labels and units).
  std::optional<std::vector<std::string>> log;
  // Rows at exactly these instants (increasing, within the run) instead of
  // the interval's grid; excludes `interval`. The rows are the solver's
  // dense output there, as on the grid: no interpolation between rows.
  std::vector<double> times;
  // Columns (by name) kept in memory besides what goes to the sink
  // (blocks::Results::Column after the run).
  std::vector<std::string> keep;
  const volatile std::sig_atomic_t* interrupt = nullptr;  // see Simulator::SetInterruptFlag
  std::function<void(double)> progress;                   // after every row; may throw to end the run
};

enum class Status { kOk, kStopped, kFailed, kInterrupted };

struct RunResult {
  Status status = Status::kOk;
  double t_reached = 0.0;
  std::string reason;  // stopped: the control script's reason; failed or interrupted: what happened
  int signal = 0;      // interrupted: the signal that ended it
  blocks::RunOutcome outcome;  // the Simulator's own account
  blocks::SolverStats stats;
  std::vector<blocks::EventRecord> events;
  std::vector<blocks::ReportFigure> figures;
  std::vector<Column> columns;  // names and units, time first
  long long rows = 0;           // rows recorded
  double wall_seconds = 0.0;    // the simulator's run alone (no load, build or sink set-up)
};

class Model;

// A run made ready: its Simulator exists (to be watched: row observers,
// size estimates) but has not run. Made by Model::Prepare; run it once.
class PreparedRun {
 public:
  blocks::Simulator& simulator() { return *sim_; }
  const diagrams::LoadedDiagram& loaded() const { return *loaded_; }
  const std::vector<Column>& columns() const { return columns_; }
  // Runs with rows going to `sink` (not owned; nullptr: no rows kept, but
  // RunOptions::keep), from t_start to t_end.
  RunResult Run(blocks::RowSink* sink);

 private:
  friend class Model;
  PreparedRun(const diagrams::LoadedDiagram& loaded, const RunOptions& options);
  const diagrams::LoadedDiagram* loaded_;
  RunOptions options_;
  std::unique_ptr<blocks::Simulator> sim_;
  std::vector<Column> columns_;
  bool ran_ = false;
};

class Model {
 public:
  // Reads and builds `path`. Throws InputError (file:line) for bad input.
  explicit Model(const std::string& path, LoadOptions options = {});
  // From a description already read (each worker of a sweep its own Model).
  explicit Model(diagrams::DiagramDescription description, LoadOptions options = {});

  // The diagram as built with the current settings (rebuilt first if Set
  // changed them). It refers to this Model: valid until the next rebuild.
  const diagrams::LoadedDiagram& Loaded();
  const diagrams::DiagramDescription& description() const { return description_; }
  std::vector<Identifier> Identifiers();
  // Every output port a run can log ("block.port"), in block order.
  std::vector<std::string> LoggableSignals();

  // `name` (any case) takes `value` in the unit of its own definition, as
  // --set NAME=VALUE gives it; SetExpression as --set NAME=EXPR. An unknown
  // name (InputError with the nearest names) or a derived identifier is
  // refused as --set refuses it. Takes effect at the next run.
  void Set(const std::string& name, double value);
  void SetExpression(const std::string& name, const std::string& expression);
  // Every setting at once (variants, --set values, overrides, sandbox), as
  // if the model had been made with them; Set goes on from these. Nothing
  // is rebuilt when they are what the current build was made with.
  void SetOptions(LoadOptions options) { options_ = std::move(options); }
  const LoadOptions& options() const { return options_; }

  // The next run, ready (see PreparedRun); builds the diagram anew unless the
  // current build is fresh (never run, same settings).
  PreparedRun Prepare(const RunOptions& options = {});
  RunResult Run(const RunOptions& options = {}, blocks::RowSink* sink = nullptr);

 private:
  int FindIdentifier(const std::string& name);
  LoadOptions Effective(const RunOptions& options) const;
  void Build(const LoadOptions& options);

  diagrams::DiagramDescription description_;
  LoadOptions options_;                 // with every Set
  LoadOptions built_with_;              // what loaded_ was built with (a run's overrides included)
  LoadOptions built_from_;              // options_ when loaded_ was built
  std::unique_ptr<diagrams::LoadedDiagram> loaded_;
  bool used_ = false;                   // loaded_ has been handed to a run
};

}  // namespace mechflow::run
