#pragma once
// BlockContext: one block's view of the diagram's run-time values.
//
// It is a pair of pointers (the diagram Context and the block's layout), built
// on the stack for each call: no allocation, no lookup. Spans point straight
// into the Context's packed arrays.
//
// Everything a run changes lives in the Context, never in the blocks: values
// (signals, states) and a block's scratch (work arrays, caches, figures kept
// for reports). So one built diagram can be run by several Contexts at once,
// one per thread, as long as its blocks call no shared Lua state
// (scripting/lua_state.h).

#include <cstdint>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace mechflow::blocks {

// Where one block's values sit in the Context's packed arrays. Filled once by
// the diagram builder.
struct BlockLayout {
  int block = 0;                   // the block's index: its scratch in Context::scratch
  std::vector<int> input_offset;   // per input port: offset of its driving signal
  std::vector<int> input_width;
  std::vector<int> output_offset;  // per output port: offset in Context::signals
  std::vector<int> output_width;
  int first_state = 0;             // into the continuous state vector
  int num_states = 0;
  int first_discrete = 0;          // into Context::discrete
  int num_discrete = 0;
  int first_crossing = 0;          // into the zero-crossing vector
  int num_crossings = 0;
};

// A block's (or an algebraic loop's) run-time scratch: work arrays sized
// once, caches, figures kept for reports. Made by Block::MakeScratch when a
// Context is prepared for a run (InitializeStates), owned by the Context.
class BlockScratch {
 public:
  virtual ~BlockScratch() = default;
};

// All run-time values of a diagram. Owned by the simulator; the continuous
// state, its derivative and the zero-crossing values are pointers because they
// live in SUNDIALS vectors during a solver call.
struct Context {
  double time = 0.0;
  std::vector<double> signals;   // every output port, packed
  std::vector<double> discrete;  // modes and held samples
  double* x = nullptr;           // continuous state
  double* xdot = nullptr;        // its derivative (valid in CalcDerivatives)
  double* crossings = nullptr;   // zero-crossing values (valid in CalcZeroCrossings)
  // Incremented whenever time or state may have changed, so a block may cache
  // work shared between its output ports (e.g. mechanism kinematics).
  std::uint64_t evaluation = 0;
  // True while a right-hand side is evaluated: the derivatives follow the
  // outputs in the same evaluation, so a block may do work they share while
  // computing an output. False for output rows and root functions.
  bool derivatives_follow = false;
  // Per block (by index; null for a block that needs none) and per algebraic
  // loop: made afresh by InitializeStates (blocks/framework/evaluation.h).
  std::vector<std::unique_ptr<BlockScratch>> scratch;
  std::vector<std::unique_ptr<BlockScratch>> loop_scratch;
  std::unique_ptr<BlockScratch> run_claim;  // Diagram::run_claim's, held while the run's Context lives
};

// Block `block`'s scratch in a run's Context, of type T, for figures read
// after the run; null when the Context was never prepared (no run started).
// Throws std::logic_error when the block's scratch is not a T (the wrong
// block index or Context).
template <typename T>
const T* RunScratch(const Context& run, int block) {
  if (run.scratch.empty()) return nullptr;
  const auto i = static_cast<std::size_t>(block);
  const T* s = i < run.scratch.size() ? dynamic_cast<const T*>(run.scratch[i].get()) : nullptr;
  if (!s) throw std::logic_error("block " + std::to_string(block) + " of this run is not the block asked about");
  return s;
}

class BlockContext {
 public:
  BlockContext(Context* ctx, const BlockLayout* layout) : ctx_(ctx), layout_(layout) {}

  double time() const { return ctx_->time; }
  std::uint64_t evaluation() const { return ctx_->evaluation; }
  bool derivatives_follow() const { return ctx_->derivatives_follow; }

  std::span<const double> input(int port) const {
    return {ctx_->signals.data() + layout_->input_offset[port],
            static_cast<std::size_t>(layout_->input_width[port])};
  }
  double input_scalar(int port) const { return ctx_->signals[layout_->input_offset[port]]; }
  std::span<double> output(int port) const {
    return {ctx_->signals.data() + layout_->output_offset[port],
            static_cast<std::size_t>(layout_->output_width[port])};
  }
  // Continuous states. Blocks change them only in Initialize, the event and
  // sample-hit handlers and UpdateModes (an integrator resets on a trigger
  // that jumped, or snaps onto a limit it has reached); the solver is
  // re-initialised after each of those. Everywhere else (outputs,
  // derivatives, zero crossings, Project) they are read-only.
  std::span<double> state() const {
    return {ctx_->x + layout_->first_state, static_cast<std::size_t>(layout_->num_states)};
  }
  std::span<double> derivative() const {
    return {ctx_->xdot + layout_->first_state, static_cast<std::size_t>(layout_->num_states)};
  }
  // Discrete states (modes, held samples). Changed only in Initialize, event,
  // sample-hit and UpdateModes handlers.
  std::span<double> discrete() const {
    return {ctx_->discrete.data() + layout_->first_discrete,
            static_cast<std::size_t>(layout_->num_discrete)};
  }
  std::span<double> zero_crossings() const {
    return {ctx_->crossings + layout_->first_crossing,
            static_cast<std::size_t>(layout_->num_crossings)};
  }
  // The block's own scratch, of the type its MakeScratch makes. A Context
  // that InitializeStates did not prepare has none: a programming error.
  template <typename T>
  T& scratch() const {
    const std::size_t b = static_cast<std::size_t>(layout_->block);
    if (b >= ctx_->scratch.size() || !ctx_->scratch[b]) [[unlikely]]
      throw std::logic_error("a block's scratch is missing: prepare the Context with InitializeStates first");
    return static_cast<T&>(*ctx_->scratch[b]);
  }

 private:
  Context* ctx_;
  const BlockLayout* layout_;
};

}  // namespace mechflow::blocks
