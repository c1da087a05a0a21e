#pragma once
// ControlCalls: the calls of a run's control (blocks/solver/run_control.h) and what
// they leave behind: whether the model changed (then the modes are settled
// again here and the simulator re-initialises), and a request to stop.

#include <limits>
#include <string>

#include "blocks/framework/block_context.h"
#include "blocks/framework/diagram.h"
#include "blocks/solver/run_control.h"

namespace mechflow::blocks {

class ControlCalls {
 public:
  // `t_end`: the run's end, as the control reads it.
  ControlCalls(const Diagram& diagram, Context* ctx, double t_end) : diagram_(diagram), ctx_(*ctx), t_end_(t_end) {}

  // Not owned, nullptr for none.
  void Set(RunControl* control) { control_ = control; }
  bool active() const { return control_ != nullptr; }

  // A new run: no stop requested.
  void Reset() {
    stop_requested_ = false;
    stop_reason_.clear();
  }
  // Calls the control (`call` is one of its methods) with the outputs
  // evaluated at (t, x) (`evaluated`: they are current there); returns true
  // when it changed something. Throws SimulationError when the modes do not
  // settle after its changes.
  bool Call(double t, double* x, void (RunControl::*call)(ControlPoint&), bool evaluated = false);
  // When the control's next timer runs, +infinity for none (or no control).
  double NextTimer() const { return control_ ? control_->NextTimer() : std::numeric_limits<double>::infinity(); }

  bool stop_requested() const { return stop_requested_; }
  const std::string& stop_reason() const { return stop_reason_; }

 private:
  class Point;  // the ControlPoint the control sees

  const Diagram& diagram_;
  Context& ctx_;
  const double t_end_;
  RunControl* control_ = nullptr;
  bool changed_ = false;
  bool stop_requested_ = false;
  std::string stop_reason_;
};

}  // namespace mechflow::blocks
