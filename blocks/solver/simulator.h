#pragma once
// Simulator: integrates a built diagram with CVODE and records logged signals.
//
// Method: CVODE BDF (variable order 1..5), Newton iteration with a direct
// linear solver. This is the stiff workhorse: friction regularisation and
// contact stiffness make the problems this tool is for stiff. The linear
// solver (dense, sparse or krylov) is chosen once per diagram
// (blocks/solver/linear_solver_choice.h). The whole run has subnormal
// numbers flushed to zero (blocks/solver/flush_denormals.h).
//
// One run, as pseudocode (Run, with the pieces in blocks/solver/):
//   initialise block states; settle modes; the control's start; sample hits
//     and timers due at t_start; start CVODE            (StartAt)
//   record row at t_start; start the crossing search there
//   while t < t_end and the control has not stopped the run:
//     stop := min(next sample hit, next control timer, t_end)
//                                     (the integrator never passes it)
//     an output time at the last event: its row          (RowAtLastInstant)
//     take one step (CV_ONE_STEP) towards stop (and, when a block declares a
//       projection, project after it)                     (TakeStep)
//     on solver failure: restart the method once it has gone some steps
//       (RestartPolicy), else record the last state reached and report time
//       and flag                                          (Restart, Fail)
//     at each output time inside the step, then at its end (ScanStep):
//       interpolate the state, evaluate the crossing functions (at an output
//       time with every output, which the row then takes) and compare them
//       with the last check (CrossingEvents, blocks/solver/crossing_search.h,
//       CVODE's rules)
//       on a crossing: locate it on the step's interpolant; at t_e: outputs
//         at t_e; each fired block handles its crossing (may change modes and
//         states); settle modes; re-initialise; a crossing that fires 100
//         times at one instant fails the run (RefiringLimit)   (EventAt)
//       else at an output time: the control's Output call, then the row
//         (RowInStep)
//     on reaching the stop: periodic blocks update, the control's timers
//       run; settle; re-initialise; the row if one is due   (ArriveAtStop)
//   the control's finish                                   (EndRun)
// Run is Start, AdvanceTo(t_end) and Finish; a co-simulation (fmi/) calls
// them one by one, pausing inside a step at each communication time and
// going on from there as if it had not paused, unless the held inputs
// changed meanwhile (then the integrator restarts there: RestartHere).
// The crossings are checked where CVODE's own root finding, driven to each
// output time in CV_NORMAL mode, would check them, so events and rows are
// those of that scheme; driving it so cost a CVode call, two interpolations
// and two evaluations per row (bench/README.md, P1).
//
// Modes (stick/slip, saturation, limits) change only at those event points, so
// the right-hand side is smooth inside every step.

#include <csignal>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "blocks/framework/block_context.h"
#include "blocks/framework/diagram.h"
#include "blocks/outputs/report.h"
#include "blocks/outputs/results.h"
#include "blocks/solver/callback_failures.h"
#include "blocks/solver/control_calls.h"
#include "blocks/solver/crossing_events.h"
#include "blocks/solver/frozen_motion.h"
#include "blocks/solver/grid_time.h"
#include "blocks/solver/linear_solver_choice.h"
#include "blocks/solver/report_watch.h"
#include "blocks/solver/row_recorder.h"
#include "blocks/solver/run_control.h"
#include "blocks/solver/sample_hits.h"
#include "blocks/solver/solver_options.h"

namespace mechflow::blocks {

class CvodeRun;

struct RunOutcome {
  bool ok = true;
  double t_reached = 0.0;
  std::string failure;  // when !ok: solver flag and reason
  bool stopped = false;     // ended early by its control (ok stays true)
  std::string stop_reason;  // when stopped: the control's reason
  int interrupted = 0;      // the signal that ended it (SIGINT, SIGTERM, SIGHUP), else 0; ok is false then
};

class Simulator {
 public:
  // `logged` are resolved signals (Diagram::ResolveSignal) recorded at every
  // output time. Throws InputError when the options are not usable.
  Simulator(const Diagram& diagram, SolverOptions options, std::vector<SignalRef> logged);
  ~Simulator();

  // Figures to locate during every run (blocks/outputs/report.h), each step of the
  // integrator watched on its interpolant. Signals must be scalar or
  // indexed within their width (InputError otherwise).
  void SetReports(std::vector<ReportRequest> reports) { reports_.Set(std::move(reports)); }

  // A control (e.g. a Lua control script) called during every run; not
  // owned, nullptr for none. See blocks/solver/run_control.h for when it runs.
  void SetControl(RunControl* control) { control_.Set(control); }

  // A flag a signal handler sets (to the signal's number) to end the run:
  // it is read before every output row, so the run ends at the last row
  // taken, every row complete. Not owned.
  void SetInterruptFlag(const volatile std::sig_atomic_t* flag) { interrupt_ = flag; }

  // Runs from t_start to t_end. `progress(t)` is called after every output row.
  RunOutcome Run(const std::function<void(double)>& progress = {});

  // The run in pieces (as Run, which is these three). Start: from t_start
  // (the rows there). AdvanceTo(t), t_start <= t <= t_end: integrates until
  // the solution is known at t, the context evaluated there (its signals are
  // t's); returns false when the run ended short of t (failed, stopped by its
  // control, interrupted: outcome() says which). Finish: the control's
  // finish and the outcome; no AdvanceTo after it.
  void Start(const std::function<void(double)>& progress = {});
  bool AdvanceTo(double t);
  RunOutcome Finish();
  // After AdvanceTo, when discrete states (held inputs) were changed through
  // mutable_context(): the run goes on from the current time with them, the
  // integrator restarted (what the paused step computed beyond is void).
  void RestartHere();
  // Evaluates every output at the current time when neither a pause nor a
  // row there did (AdvanceTo ending at a sample hit or timer between rows).
  void EvaluateHere();
  Context& mutable_context() { return ctx_; }
  // Where the run stands (the last row, event, stop or pause) and how it went so far.
  double time() const { return at_.t; }
  const RunOutcome& outcome() const { return outcome_; }

  const Results& results() const { return results_; }
  // Rows go to `sink` (not owned) as they are recorded, and only the
  // columns in `keep` stay in memory (blocks/outputs/results.h). Call before Run.
  void StreamRows(RowSink* sink, std::vector<int> keep) { results_.Stream(sink, std::move(keep)); }
  // `observer` (not owned) sees every row after it is recorded. Call before Run.
  void SetRowObserver(RowObserver* observer) { rows_.SetObserver(observer); }
  const SolverStats& stats() const { return stats_; }
  const std::vector<EventRecord>& events() const { return crossings_.events(); }
  // The reports' figures so far (also in results().figures() after a run).
  std::vector<ReportFigure> figures() const { return reports_.figures(); }
  const SolverOptions& options() const { return options_; }
  // The sparse Jacobian when the run uses one (chosen at construction), else
  // nullptr.
  const ColouredJacobian* sparse_jacobian() const { return solver_choice_.sparse.get(); }
  // The time, state and signals the run last evaluated (after a run: where it ended).
  const Context& context() const { return ctx_; }

  // Smallest state count for which kAuto considers a sparse Jacobian.
  static constexpr int kSparseMinStates = LinearSolverChoice::kSparseMinStates;
  // Smallest state count for which kAuto picks the Krylov solver.
  static constexpr int kKrylovMinStates = LinearSolverChoice::kKrylovMinStates;

 private:
  // Where the run stands: its results reach t (the last row, event or stop).
  struct Cursor {
    double t = 0.0;
    long next_output = 1;  // index of the next output time
    long steps = 0;        // since t (options_.max_steps)
  };
  // The step CVODE took last, while its rows and crossings are being taken:
  // AdvanceTo may pause inside it and the next one goes on with it.
  struct OpenStep {
    bool open = false;
    double t_ret = 0.0, stop = 0.0;
    bool at_stop = false;
    bool frozen_checked = false;  // FrozenMotionGuard saw this step
    std::vector<double> x_pause;  // the state at the pause
  };
  enum class Scan { kDone, kCut, kPaused };

  // `options` with its defaults filled in; throws InputError when they, or a
  // periodic block's sample period, are not usable.
  static SolverOptions Checked(const Diagram& diagram, SolverOptions options);

  // Fresh per-run state: CVODE's objects, counters, results, reports.
  void BeginRun(const std::function<void(double)>& progress);
  // Initial states and modes, the control's start, the hits due at t0; CVODE
  // started; the first row; the crossing search started.
  void StartAt(double t0);
  // The next output time, before or at `stop` (a hair before it counts as it).
  double NextRowTime(double stop) const;
  // The next instant the integrator must stop at: sample hit, timer or t_end.
  double NextStop() const;
  // A row at an output time that coincides with the last event or stop.
  void RowAtLastInstant();
  // One CVODE step towards stop (sized, after a start, towards t_out);
  // returns CVode's flag and where the step ended in *t_ret.
  int TakeStep(double stop, double t_out, double* t_ret);
  // After repeated failures at one step: restarts the method from the last
  // accepted point when RestartPolicy allows; returns whether it did.
  bool Restart(int flag);
  // Ends a run the solver cannot continue: the last state reached is
  // recorded when it can be, and `outcome` says why.
  void Fail(int flag, RunOutcome* outcome);
  // The output times inside the step that ended at t_ret, then its end: rows
  // and crossings in order. kCut when an event, a control's change or a stop
  // cut the step short (the rest of it is void); kPaused when it reached
  // `limit` inside the step (crossings checked and the context evaluated
  // there), the rest to be scanned by the next AdvanceTo.
  Scan ScanStep(double t_ret, double stop, bool at_stop, double limit);
  // The pause at `limit` inside the step: no crossing before it.
  Scan PauseAt(double limit, double t_ret);
  // The state at t_check inside the step that ended at t_ret, into x.
  void StateInStep(double t_check, double t_ret, double* x);
  // Continues from the crossing located at t_root (state x_root).
  void EventAt(double t_root, const double* x_root);
  // The row at t_check inside the step (state x, outputs evaluated there);
  // returns true when the run cannot go on from this step.
  bool RowInStep(double t_check, double* x);
  // At the stop the step reached: sample hits, timers, re-initialisation, and
  // the row due there.
  void ArriveAtStop(double t_ret);
  // How the run ended, the last row of a stopped run, and the control's finish.
  void EndRun(RunOutcome* outcome);
  // Settles the modes and restarts CVODE and the crossing search at t.
  void Reinitialize(double t);
  // Lets the reports see the solution up to t, within the last step.
  void WatchTo(double t);
  void Progress(double t) const {
    if (progress_) progress_(t);
  }
  bool Interrupted() const { return interrupt_ && *interrupt_ != 0; }

  const Diagram& diagram_;
  SolverOptions options_;
  std::vector<SignalRef> logged_;
  Results results_;
  SolverStats stats_;
  Context ctx_;
  OutputGrid grid_;
  LinearSolverChoice solver_choice_;
  CallbackFailures failures_;
  RowRecorder rows_;
  FrozenMotionGuard frozen_;
  ReportWatch reports_;
  CrossingEvents crossings_;
  SampleHits sample_hits_;
  ControlCalls control_;
  std::unique_ptr<CvodeRun> cvode_;
  std::vector<double> at_root_;  // the state at a located crossing
  Cursor at_;
  OpenStep step_;
  RunOutcome outcome_;
  std::function<void(double)> progress_;  // Start's, until Finish (a copy: a run in steps outlives the caller's)
  const volatile std::sig_atomic_t* interrupt_ = nullptr;
};

}  // namespace mechflow::blocks
