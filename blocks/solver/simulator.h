#pragma once
// Simulator: integrates a built diagram with CVODE and records logged signals.
//
// Method: CVODE BDF (variable order 1..5), Newton iteration with a direct
// linear solver. This is the stiff workhorse: friction regularisation and
// contact stiffness make the problems this tool is for stiff. Three linear
// solvers:
//   dense:  CVODE's dense matrix and difference-quotient Jacobian (n
//           right-hand sides per Jacobian, O(n^3) factorisation); with rate
//           pairs (q' = v) the positions are eliminated before the LU
//           (blocks/solver/second_order_solver.h);
//   sparse: the diagram's structural pattern (blocks/solver/sparsity.h), filled by
//           coloured difference quotients (one right-hand side per colour,
//           blocks/solver/coloured_jacobian.h) into a compressed-column matrix that
//           KLU factors. The Newton matrix I - gamma J is formed here
//           (CVodeSetLinSysFn): CVODE's own construction of it for a sparse
//           matrix costs O(n^2) (../shared/BENCH.md, known traps);
//   krylov: GMRES (SPGMR), matrix-free: each iteration one right-hand side
//           for J v by a difference quotient, O(n) for a mechanism; the
//           preconditioner solves the rows q' = v exactly (identity
//           elsewhere). No Jacobian, no factorisation: for large mechanisms
//           whose Jacobian is dense (a long serial chain: every acceleration
//           reads every coordinate), where dense costs n^2 per Jacobian and
//           n^3 per factorisation.
// Dense and sparse take the blocks' analytic Jacobian instead of difference
// quotients when the diagram has one (blocks/solver/analytic_jacobian.h; a sliding
// mechanism, mech/sliding_jacobian.h): no right-hand sides per Jacobian.
// kAuto picks sparse when the diagram has at least kSparseMinStates states and
// its pattern needs at most a quarter as many colours as states (so a fill
// costs at most n/4 right-hand sides); otherwise krylov when it has at least
// kKrylovMinStates states of which rate pairs are at least a quarter and no
// block projects (closed loops, quaternions); dense otherwise. On the P4
// chain (bench/README.md) krylov and dense break even at 50 bodies (100
// states), krylov is 2x faster at 200 and grows as N^1.2 up to 2000
// bodies. Measured on the P3
// chain (../shared/BENCH.md, CPU time): sparse wins already at 20 states
// (0.07 s against 0.14 s), by 1.2x at 30 (bench_friction, P3 N = 10),
// 1.6x at 90 and 7x at 200 (1.4 s against 10.3 s). No example diagram changes solver at this threshold (it was 100
// until every other cost of a small run had come down). The whole run has
// subnormal numbers flushed to zero (blocks/solver/flush_denormals.h).
//
// One run, as pseudocode:
//   initialise block states; settle modes; sample hits due at t_start
//   record row at t_start; start the crossing search there
//   while t < t_end:
//     stop := min(next sample hit, t_end)         (the integrator never passes it)
//     take one step (CV_ONE_STEP) towards stop (and, when a block declares a
//       projection, project after it)
//     at each output time inside the step, then at its end: interpolate the
//       state, evaluate the crossing functions (at an output time with every
//       output, which the row then takes) and compare them with the last
//       check (blocks/solver/crossing_search.h, CVODE's rules)
//     on a crossing: locate it on the step's interpolant; at t_e: outputs at
//       t_e; each fired block handles its crossing (may change modes and
//       states); settle modes; re-initialise; a crossing that fires 100 times
//       at one instant fails the run
//     else at an output time: record the row
//     on reaching a sample hit: periodic blocks update; settle; re-initialise
//   on solver failure: record the last state reached and report time and flag
// The crossings are checked where CVODE's own root finding, driven to each
// output time in CV_NORMAL mode, would check them, so events and rows are
// those of that scheme; driving it so cost a CVode call, two interpolations
// and two evaluations per row (bench/README.md, P1).
//
// Modes (stick/slip, saturation, limits) change only at those event points, so
// the right-hand side is smooth inside every step.

#include <algorithm>
#include <cmath>
#include <csignal>
#include <functional>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "blocks/framework/block_context.h"
#include "blocks/framework/diagram.h"
#include "blocks/outputs/report.h"
#include "blocks/outputs/results.h"
#include "blocks/solver/run_control.h"

#include <sundials/sundials_matrix.h>
#include <sundials/sundials_nvector.h>

namespace mechflow::blocks {

class AnalyticJacobian;
class ColouredJacobian;
class CrossingSearch;

enum class LinearSolverKind { kAuto, kDense, kSparse, kKrylov };
// Where the Newton matrices' Jacobian comes from: kAuto takes the analytic
// one when the diagram has it (blocks/solver/analytic_jacobian.h), difference
// quotients otherwise; kAnalytic refuses a diagram without it.
enum class JacobianKind { kAuto, kAnalytic, kDifferenceQuotient };

struct SolverOptions {
  double t_start = 0.0;      // [s]
  double t_end = 1.0;        // [s], > t_start
  double rtol = 1e-6;        // relative tolerance, > 0
  double atol = 1e-8;        // absolute tolerance, > 0
  double max_step = 0.0;     // [s], 0: no limit
  double initial_step = 0.0; // [s], 0: CVODE's own estimate
  long max_steps = 500000;   // steps allowed between two output times
  double output_interval = 0.0;  // [s], 0: (t_end - t_start) / 1000
  LinearSolverKind linear_solver = LinearSolverKind::kAuto;
  // Dense runs of diagrams with rate pairs (x_q' = x_v, Block::rate_pairs)
  // eliminate the positions from each Newton system
  // (blocks/solver/second_order_solver.h); false solves the whole system, as
  // before (for comparisons).
  bool second_order = true;
  JacobianKind jacobian = JacobianKind::kAuto;

  // Empty when usable, otherwise what is wrong (e.g. "rtol must be > 0").
  std::string Problem() const;
};

// Solver counters accumulated over the whole run (across re-initialisations).
struct SolverStats {
  long steps = 0;
  long rhs_evals = 0;        // by the integrator
  long jac_rhs_evals = 0;    // by the difference-quotient Jacobian; with the analytic one, the
                             // output evaluations it needed (at a state no right-hand side had just seen)
  long jac_evals = 0;
  long newton_iters = 0;
  long linear_iters = 0;     // Krylov iterations (0 with direct solvers)
  long newton_failures = 0;  // nonlinear convergence failures
  long error_test_failures = 0;
  long root_evals = 0;
  long events = 0;           // zero crossings handled
  long sample_hits = 0;
  long reinits = 0;
  long restarts = 0;         // after repeated error-test or convergence failures (a re-initialisation too)
  long projections = 0;          // projection calls (0 unless a block declares one)
  long projection_failures = 0;  // failed projections (each retries its step smaller)
  bool sparse = false;           // sparse Jacobian and KLU (otherwise dense or Krylov)
  bool krylov = false;           // GMRES with difference-quotient products J v
  bool analytic_jacobian = false;  // the blocks' exact Jacobian (blocks/solver/analytic_jacobian.h)
  int newton_size = 0;           // unknowns of each Newton system solved (fewer than states with rate pairs)
  int colours = 0;               // sparse: column groups, right-hand sides per Jacobian
  long nonzeros = 0;             // sparse: entries of the structural pattern
};

// One handled zero crossing, kept so a user can ask when contacts, impacts or
// mode switches happened without resampling the output grid.
struct EventRecord {
  double time = 0.0;   // [s], located by CVODE's root finding
  int block = 0;       // index in the diagram
  int crossing = 0;    // the block's own zero-crossing index
  int direction = 0;   // +1 rising, -1 falling
};

// Sees every row as it is recorded, with the continuous state and the
// Context's signals at that time (an animation records the bodies' poses).
class RowObserver {
 public:
  virtual ~RowObserver() = default;
  virtual void OnRow(double t, const double* x, const Context& ctx) = 0;
};

struct RunOutcome {
  bool ok = true;
  double t_reached = 0.0;
  std::string failure;  // when !ok: solver flag and reason
  bool stopped = false;     // ended early by its control (ok stays true)
  std::string stop_reason;  // when stopped: the control's reason
  int interrupted = 0;      // the signal that ended it (SIGINT, SIGTERM, SIGHUP), else 0; ok is false then
};

// Frozen motion: the same state bit for bit `dt` seconds apart although the
// slope would have moved component i by more than a thousandth of its error
// weight. Returns the first such i, or -1.
int FrozenState(std::span<const double> before, std::span<const double> after, std::span<const double> slope,
                double dt, double rtol, double atol);

class Simulator {
 public:
  // `logged` are resolved signals (Diagram::ResolveSignal) recorded at every
  // output time. Throws InputError when the options are not usable.
  Simulator(const Diagram& diagram, SolverOptions options, std::vector<SignalRef> logged);
  ~Simulator();

  // Figures to locate during every run (blocks/outputs/report.h). With reports the
  // integrator advances one internal step at a time, each step watched;
  // without, it runs to each output time at once. Signals must be scalar or
  // indexed within their width (InputError otherwise).
  void SetReports(std::vector<ReportRequest> reports);

  // A control (e.g. a Lua control script) called during every run; not
  // owned, nullptr for none. See blocks/solver/run_control.h for when it runs.
  void SetControl(RunControl* control) { control_ = control; }

  // A flag a signal handler sets (to the signal's number) to end the run:
  // it is read before every output row, so the run ends at the last row
  // taken, every row complete. Not owned.
  void SetInterruptFlag(const volatile std::sig_atomic_t* flag) { interrupt_ = flag; }

  // Runs from t_start to t_end. `progress(t)` is called after every output row.
  RunOutcome Run(const std::function<void(double)>& progress = {});

  const Results& results() const { return results_; }
  // Rows go to `sink` (not owned) as they are recorded, and only the
  // columns in `keep` stay in memory (blocks/outputs/results.h). Call before Run.
  void StreamRows(RowSink* sink, std::vector<int> keep) { results_.Stream(sink, std::move(keep)); }
  // `observer` (not owned) sees every row after it is recorded. Call before Run.
  void SetRowObserver(RowObserver* observer) { observer_ = observer; }
  const SolverStats& stats() const { return stats_; }
  const std::vector<EventRecord>& events() const { return events_; }
  // The reports' figures so far (also in results().figures() after a run).
  std::vector<ReportFigure> figures() const;
  const SolverOptions& options() const { return options_; }
  // The sparse Jacobian when the run uses one (chosen at construction), else
  // nullptr.
  const ColouredJacobian* sparse_jacobian() const { return jacobian_.get(); }

  // Smallest state count for which kAuto considers a sparse Jacobian.
  static constexpr int kSparseMinStates = 20;
  // Smallest state count for which kAuto picks the Krylov solver.
  static constexpr int kKrylovMinStates = 200;

 private:
  struct Solver;
  static int Rhs(double t, N_Vector y, N_Vector ydot, void* self);
  static int LinearSystem(double t, N_Vector y, N_Vector fy, SUNMatrix A, sunbooleantype jok,
                          sunbooleantype* jcur, double gamma, void* self, N_Vector, N_Vector, N_Vector);
  static int DenseJacobian(double t, N_Vector y, N_Vector fy, SUNMatrix j, void* self, N_Vector, N_Vector,
                           N_Vector);
  static int PreconditionRatePairs(double t, N_Vector y, N_Vector fy, N_Vector r, N_Vector z, double gamma,
                                   double delta, int side, void* self);
  static int Project(double t, N_Vector y, N_Vector correction, double tolerance, N_Vector error, void* self);
  static void ErrorHandler(int code, const char* module, const char* function, char* msg, void* self);

  int EvaluateRhs(double t, double* x, double* xdot);
  // The analytic Jacobian at (t, x), evaluating the outputs there first
  // unless the last right-hand side was at (t, x); returns 0 or a failure
  // flag for CVODE (recoverable, as a right-hand side's).
  int EvaluateAnalyticJacobian(double t, double* x);
  // Every output at (t, x), or the dynamics schedule's alone.
  void EvaluateAt(double t, double* x, bool dynamics_only = false);
  // The zero-crossing functions at (t, x) into crossing_values_, after
  // evaluating the outputs there (all of them for a row, else the dynamics
  // schedule's).
  void EvaluateCrossingsAt(double t, double* x, bool row);
  // A new start of the crossing search at (t, x) (with CVODE's).
  void StartCrossings(double t, double* x);
  // Checks the crossings at (t, x) after a step: all outputs evaluated
  // there when `row`. On a crossing between the last check and t, returns
  // true with it located (roots_found_) and the state there in x_root, at
  // *t_root; otherwise the check is accepted.
  bool CheckCrossings(double t, double* x, bool row, double* t_root, double* x_root);
  // Writes a row at (t, x); `evaluated`: every output is current there.
  void Record(double t, double* x, bool evaluated = false);
  // Before an output row: when CVODE's own time advanced since the last row
  // (no re-initialisation between) while its own state stayed the same bit
  // for bit, although its derivative there is not zero, the motion froze
  // (the step size fell below the resolution of time): throws
  // SimulationError instead of letting such rows become output.
  void RefuseFrozenState();
  // Before a row is written, with every output evaluated at t, when some
  // signal is not finite (an overflow, 0/0; Record checks the whole signal
  // vector once per row, not the right-hand side, whose Newton iterates may
  // stray and recover): throws SimulationError naming the block and port,
  // the first in schedule order.
  [[noreturn]] void RefuseNonFiniteOutputs(double t) const;
  // "block 'b' (file:line) output 'y[1]'" for the output port that holds
  // `signal` at its element, or "signal N" when no output does.
  std::string DescribeSignal(int signal) const;
  // "block 'b' (file:line) state 'x'" for a continuous state.
  std::string DescribeState(int state) const;
  // The smallest step: a few units of round-off of the run's largest time.
  static double MinimumStep(double t0, double t_end) {
    return 8.0 * std::numeric_limits<double>::epsilon() * std::max({std::abs(t0), std::abs(t_end), 1e-300});
  }
  void HandleCrossings(double t);
  void HandleSampleHits(double t);
  double NextSampleHit() const;
  void Reinitialize(double t);
  void AccumulateStats();
  // Calls the control (`call` is one of its methods) with the outputs
  // evaluated at (t, x) (`evaluated`: they are current there); returns true
  // when it changed something.
  bool CallControl(double t, double* x, void (RunControl::*call)(ControlPoint&), bool evaluated = false);
  double NextStop() const;
  // The state at t inside the last step, from its Taylor coefficients
  // (found on first use in the step).
  void InterpolateInStep(double t, double* out);
  // Lets the reports see the solution on (watched_to_, t], within the last step.
  void WatchTo(double t);
  void WatchStep(double ta, double tb);

  const Diagram& diagram_;
  SolverOptions options_;
  std::vector<SignalRef> logged_;
  Results results_;
  SolverStats stats_;
  std::vector<EventRecord> events_;
  RowObserver* observer_ = nullptr;
  Context ctx_;
  std::vector<double> row_;
  std::vector<int> row_signals_;  // per column after time: the signal it logs
  std::vector<double> row_factors_;  // and the factor to its column's unit (SignalRef::column_factor)
  std::vector<double> frozen_y_, frozen_before_, frozen_slope_;  // CVODE's state at the last row, scratch
  double frozen_tn_ = 0.0;                       // and its time
  bool frozen_valid_ = false;
  // A restart after repeated solver failures needs this many steps since
  // CVODE last started; a dead end fails again sooner and ends the run.
  static constexpr long kRestartSteps = 50;
  std::vector<int> crossing_owner_;      // crossing index -> block
  std::vector<int> roots_found_;
  std::vector<long> next_hit_;           // per periodic block: next k
  std::string callback_failure_;         // reason stored by a failed callback
  bool callback_no_solution_ = false;    // it was an algebraic loop without a solution: no step-size hint
  int callback_failures_ = 0;
  bool linear_solver_attached_ = false;
  bool projection_attached_ = false;     // CVODE's projection counters exist only then
  // A crossing that fires again and again at one instant is a modelling error
  // (a handler that leaves it where it fires again). CVODE locates each
  // refiring a hair after the last, never at the very same t, so "one
  // instant" is a run of firings of one crossing, each within
  // kInstant * max(1, |t|) seconds of the one before.
  static constexpr int kMaxEventsPerInstant = 100;
  static constexpr double kInstant = 1e-9;
  std::vector<double> last_fired_;       // per crossing: when it last fired
  std::vector<int> fired_in_a_row_;      // per crossing: firings in its current instant
  std::string solver_message_;           // last message from CVODE's error handler
  std::vector<ReportRequest> reports_;
  std::vector<ExtremumTracker> trackers_;       // one per report (its extremum kinds)
  std::vector<SignalAccumulator> accumulators_;  // one per report (the other kinds)
  double watched_to_ = 0.0;  // reports have watched the solution up to here
  // The crossings are checked by the simulator at every step end and output
  // time, as CVODE's root finding would in CV_NORMAL mode (see Run).
  std::unique_ptr<CrossingSearch> crossings_;
  std::vector<double> crossing_values_;  // at the last check
  bool probe_pending_ = false;           // a function was exactly zero at the start
  // A step with several rows: its polynomial as Taylor coefficients
  // y^(k)(tn)/k! (k = 0..order, Solver::taylor), from CVodeGetDky once per
  // step, instead of a CVodeGetDky per row (Debian's unoptimised build: 7 %
  // of P1).
  int taylor_order_ = -1;  // -1: not found for this step
  double taylor_tn_ = 0.0;
  std::unique_ptr<ColouredJacobian> jacobian_;  // sparse runs only
  std::unique_ptr<AnalyticJacobian> analytic_;  // when the run uses one
  std::vector<double> analytic_values_;         // sparse: its values on the pattern
  double rhs_t_ = 0.0;                          // analytic: the last right-hand side's time and state
  std::vector<double> rhs_x_;
  std::uint64_t rhs_at_ = 0;                    // and its ctx_.evaluation (0: none)
  std::vector<double> increments_;              // sparse: per state, for each fill
  std::vector<std::pair<int, int>> rate_pairs_;  // dense: eliminated from the Newton systems; Krylov: preconditioner
  bool krylov_ = false;                          // GMRES, matrix-free
  std::unique_ptr<Solver> solver_;
  class Point;  // the ControlPoint the control sees
  RunControl* control_ = nullptr;
  bool control_changed_ = false;
  bool stop_requested_ = false;
  const volatile std::sig_atomic_t* interrupt_ = nullptr;
  bool Interrupted() const { return interrupt_ && *interrupt_ != 0; }
  std::string stop_reason_;
};

}  // namespace mechflow::blocks
