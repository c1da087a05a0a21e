#pragma once
// The Block interface: what every element of a diagram declares and computes.
//
// A block is a *description* plus pure run-time functions. In its constructor
// it declares, once:
//   - input and output ports (name, width),
//   - direct feedthrough: which outputs depend on which inputs at the same
//     instant (default: every input feeds every output, the safe choice),
//   - the number of continuous states (integrated by the solver),
//   - the number of discrete states (modes, held samples; changed only in
//     event and sample handlers),
//   - zero-crossing functions with the direction that triggers them,
//   - its sample time (continuous, or periodic with an offset).
// At run time every method is const and works on a BlockContext, the block's
// view into the diagram's Context (time, signals, states, the block's
// scratch). All values live in the Context, so one built diagram can be run
// again from scratch, or by several Contexts at once.
//
// Outputs are computed per port (DoCalcOutput(port, ...)) so the scheduler can
// order ports, not blocks: a mechanism whose positions do not depend on its
// force inputs may feed those positions back into the same mechanism without
// forming an algebraic loop.
//
// Run-time methods must not allocate, parse text or look names up; do that in
// the constructor. They report bad numbers by throwing SimulationError, which
// the simulator turns into a failed (or retried) step.

#include <algorithm>
#include <cmath>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "blocks/framework/block_context.h"

namespace mechflow::blocks {

struct PortSpec {
  std::string name;
  int width = 1;
};

// Optional structural sparsity of a block (for sparse Jacobians): which of
// its own states and input ports each state derivative and each output port
// reads. Lists hold local indices, sorted. An output's dependence on inputs
// is its declared feedthrough. A missing entry makes the diagram's Jacobian
// wrong; an extra one only costs time, so declare the superset when unsure.
struct BlockSparsity {
  std::vector<std::vector<int>> derivative_states;  // per state: the states its derivative reads
  std::vector<std::vector<int>> derivative_inputs;  // per state: the input ports its derivative reads
  std::vector<std::vector<int>> output_states;      // per output port: the states it reads
};

// Which sign change of a zero-crossing function is an event.
enum class CrossingDirection { kRising, kFalling, kEither };

// Continuous (period 0) or periodic: hits at offset + k * period, k = 0, 1, ...
struct SampleTime {
  double period = 0.0;  // [s]
  double offset = 0.0;  // [s]
  bool is_periodic() const { return period > 0.0; }
};

// At most this many hits of one period over a run: a period so small that a
// run could not get through its hits is refused rather than left to hang.
inline constexpr double kMaxSampleHits = 1e8;

// "" when `period` (a block's or a script timer's) can be run from t_start to
// t_end: finite, > 0, at most kMaxSampleHits hits, and larger than the
// spacing of doubles near the run's times allows to tell apart (1e-12 of the
// largest |t|). Otherwise what is wrong and what period would do.
std::string SamplePeriodProblem(double period, double t_start, double t_end);

// True when two instants are one up to rounding (1e-12 relative, the
// resolution SamplePeriodProblem asks periods to exceed): 3 * 0.1 is the
// instant 0.3.
inline bool SameInstant(double a, double b) {
  return std::abs(a - b) <= 1e-12 * std::max({1.0, std::abs(a), std::abs(b)});
}

// One entry of a block's analytic Jacobian: d derivative[row] / d state[column],
// block-local indices.
struct JacobianEntry {
  int row, column;
  double value;
};

class Block {
 public:
  Block(std::string type, std::string name);
  virtual ~Block() = default;
  Block(const Block&) = delete;
  Block& operator=(const Block&) = delete;

  const std::string& type() const { return type_; }
  const std::string& name() const { return name_; }

  // --- declared structure -------------------------------------------------
  int num_inputs() const { return static_cast<int>(inputs_.size()); }
  int num_outputs() const { return static_cast<int>(outputs_.size()); }
  const PortSpec& input_port(int i) const { return inputs_.at(i); }
  const PortSpec& output_port(int i) const { return outputs_.at(i); }
  // Index of the named port, or -1.
  int FindInput(std::string_view port_name) const;
  int FindOutput(std::string_view port_name) const;
  // True when output `out` depends on input `in` at the same instant.
  bool HasFeedthrough(int in, int out) const;

  int num_states() const { return static_cast<int>(state_names_.size()); }
  const std::string& state_name(int i) const { return state_names_.at(i); }
  int num_discrete_states() const { return num_discrete_; }
  int num_zero_crossings() const { return static_cast<int>(crossings_.size()); }
  CrossingDirection crossing_direction(int i) const { return crossings_.at(i); }
  const SampleTime& sample_time() const { return sample_time_; }
  bool has_projection() const { return has_projection_; }
  // Pairs (position, rate) of this block's states whose derivative is the
  // other state itself, x_position' = x_rate exactly (a joint coordinate and
  // its velocity). The Newton system is then solved in fewer unknowns
  // (blocks/solver/second_order_solver.h).
  const std::vector<std::pair<int, int>>& rate_pairs() const { return rate_pairs_; }
  // The declared sparsity, or nullptr: every derivative then reads every
  // state and input, and every output every state (the safe default). A
  // block whose sparsity is costly to find may find it here, on first use
  // (a run asks; loading and checking do not).
  virtual const BlockSparsity* sparsity() const {
    return sparsity_.derivative_states.empty() ? nullptr : &sparsity_;
  }

  // --- run time ------------------------------------------------------------
  // The block's run-time scratch, made once per run when the Context is
  // prepared (InitializeStates), or null when it needs none. Whatever a
  // run-time method changes besides the Context's values lives there (work
  // arrays, caches between output ports, figures read after the run), never
  // in the block: one built diagram may run on several threads at once. The
  // run-time methods reach it through ctx.scratch<T>().
  virtual std::unique_ptr<BlockScratch> MakeScratch() const { return nullptr; }
  // Sets initial continuous and discrete states (inputs are not yet valid).
  void Initialize(const BlockContext& ctx) const { DoInitialize(ctx); }
  // Computes output port `port` from time, states and (feedthrough) inputs.
  void CalcOutput(int port, const BlockContext& ctx) const { DoCalcOutput(port, ctx); }
  // Writes the time derivative of the continuous states.
  void CalcDerivatives(const BlockContext& ctx) const { DoCalcDerivatives(ctx); }
  // Writes the zero-crossing function values.
  void CalcZeroCrossings(const BlockContext& ctx) const { DoCalcZeroCrossings(ctx); }
  // Zero-crossing `index` fired (direction +1 rising, -1 falling). The block
  // may change its discrete and continuous states; inputs and outputs hold
  // the values just before the event.
  void OnZeroCrossing(int index, int direction, const BlockContext& ctx) const {
    DoZeroCrossing(index, direction, ctx);
  }
  // Periodic blocks: called at each sample hit with inputs valid.
  void OnSampleHit(const BlockContext& ctx) const { DoSampleHit(ctx); }
  // After initialisation and after every event: make modes agree with the
  // current inputs and states (e.g. a saturation whose input jumped). The
  // block may change continuous states too (an integrator resets on a jumped
  // trigger). Returns true when a mode or state changed, so outputs must be
  // recomputed.
  bool UpdateModes(const BlockContext& ctx) const { return DoUpdateModes(ctx); }
  // A static equilibrium search (analysis/linearization.h) at a candidate
  // state at rest, inputs valid: make modes agree with it as a state at rest
  // has them (a sliding friction element sticks). Returns true when a mode or
  // state changed. By default UpdateModes.
  bool UpdateModesAtRest(const BlockContext& ctx) const { return DoUpdateModesAtRest(ctx); }
  // Blocks whose states live on a manifold (closed loops, unit quaternions)
  // declare a projection (DeclareProjection). After every step it takes, the
  // solver asks each of them for `correction`: this block's slice of the
  // change (same layout as its states) that puts ctx.state() back on the
  // manifold; the solver adds it. Here:
  //   - ctx.time() and ctx.state() are current; the states are read-only
  //     (they are the solver's own vector), and inputs and outputs are not
  //     evaluated for this call, so they may be stale;
  //   - `error` is the block's slice of the solver's local error estimate,
  //     empty when the solver passes none. The block may project it onto the
  //     manifold's tangent space too, or leave it alone: on a unit circle,
  //     projecting it made CVODE fall back to order 1 and take 40 times the
  //     steps, so leave it unless a measurement says otherwise;
  //   - `weights` is the block's slice of the solver's error weights,
  //     1 / (rtol |x| + atol), empty when there are none: a correction c
  //     passes the solver's error test when the RMS of c * weights is below
  //     1, so a block whose correction carries round-off that can exceed
  //     the tolerance (a loop near a singular position) sizes it by them;
  //   - it must not allocate; it throws SimulationError when it cannot
  //     project, and the solver retries the step with a smaller one, failing
  //     the run with the block's message if that keeps happening.
  // Projection removes the integrator's drift from a manifold that the exact
  // solution keeps; it is no cure for equations that leave the manifold.
  // The solver projects only after steps, never at the start or after an
  // event: Initialize must put the states on the manifold, and so must any
  // event, sample-hit or UpdateModes handler that changes them.
  void Project(const BlockContext& ctx, std::span<double> correction, std::span<double> error,
               std::span<const double> weights) const {
    DoProject(ctx, correction, error, weights);
  }
  // Analytic Jacobian: empty when the block gives the exact
  // derivatives of its state derivatives with respect to its own states, its
  // inputs held (CalcStateJacobian); else why not, as a sentence.
  virtual std::string StateJacobianUnavailable() const { return "a " + type() + " block computes none"; }
  // Replaces `entries` with those derivatives at the context's time and
  // state (repeated entries add), where the diagram's outputs were computed.
  virtual void CalcStateJacobian(const BlockContext&, std::vector<JacobianEntry>* entries) const {
    entries->clear();
  }
  // After a failed run, with the run's context: what the block knows about
  // why (e.g. a mechanism at a singular position), as a sentence; empty when
  // it knows nothing.
  virtual std::string FailureNote(const BlockContext&) const { return {}; }
  // What zero crossing `index` firing in `direction` meant, for the event
  // log (`mechflow run --verbose`); "" when the block has no words for it.
  virtual std::string CrossingName(int /*index*/, int /*direction*/) const { return {}; }
  // The unit of an output's values ("m", "N"), "" when the block cannot know.
  virtual std::string OutputUnit(int /*port*/) const { return {}; }
  // The shortest time over which the block's outputs change by themselves,
  // inputs and states held (a source's period); infinity for none. A report
  // watches the solution between the integrator's steps, which need not
  // follow a signal that no state depends on: it must look this closely.
  virtual double OwnTimeScale() const { return INFINITY; }

 protected:
  // Declarations, for constructors only. Return the new port's index.
  int DeclareInputPort(std::string port_name, int width = 1);
  int DeclareOutputPort(std::string port_name, int width = 1);
  // Marks output `out` as (not) depending on input `in` at the same instant.
  void SetFeedthrough(int in, int out, bool direct);
  // Marks every output as depending on no input (pure state/time outputs).
  void DeclareNoFeedthrough();
  // Declares `n` more continuous states named `<prefix>[i]` (or `prefix` if n == 1).
  void DeclareContinuousStates(int n, const std::string& prefix = "x");
  void DeclareDiscreteStates(int n) { num_discrete_ += n; }
  int DeclareZeroCrossing(CrossingDirection direction);
  void DeclarePeriodicSampleTime(double period, double offset);
  void DeclareProjection() { has_projection_ = true; }
  // Declares x_position' = x_rate, exactly, at every evaluation (see
  // rate_pairs()); a position may not be another pair's rate.
  void DeclareRatePair(int position, int rate);
  // After the ports and states are declared: sizes must match them
  // (std::logic_error otherwise).
  void DeclareSparsity(BlockSparsity sparsity);

  virtual void DoInitialize(const BlockContext&) const {}
  virtual void DoCalcOutput(int port, const BlockContext& ctx) const = 0;
  virtual void DoCalcDerivatives(const BlockContext&) const {}
  virtual void DoCalcZeroCrossings(const BlockContext&) const {}
  virtual void DoZeroCrossing(int, int, const BlockContext&) const {}
  virtual void DoSampleHit(const BlockContext&) const {}
  virtual bool DoUpdateModes(const BlockContext&) const { return false; }
  virtual bool DoUpdateModesAtRest(const BlockContext& ctx) const { return DoUpdateModes(ctx); }
  virtual void DoProject(const BlockContext&, std::span<double>, std::span<double>, std::span<const double>) const {}

 private:
  std::string type_;
  std::string name_;
  std::vector<PortSpec> inputs_;
  std::vector<PortSpec> outputs_;
  // explicit (in, out) pairs without feedthrough; everything else feeds through
  std::vector<std::pair<int, int>> no_feedthrough_;
  bool no_feedthrough_at_all_ = false;
  std::vector<std::string> state_names_;
  int num_discrete_ = 0;
  std::vector<CrossingDirection> crossings_;
  SampleTime sample_time_;
  bool has_projection_ = false;
  std::vector<std::pair<int, int>> rate_pairs_;
  BlockSparsity sparsity_;
};

}  // namespace mechflow::blocks
