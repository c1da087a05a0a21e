#include "blocks/solver/control_calls.h"

#include <utility>

#include "blocks/framework/evaluation.h"
#include "blocks/solver/evaluate_at.h"
#include "mech/errors.h"

namespace mechflow::blocks {

class ControlCalls::Point final : public ControlPoint {
 public:
  explicit Point(ControlCalls& calls) : calls_(calls) {}
  double time() const override { return calls_.ctx_.time; }
  double end_time() const override { return calls_.t_end_; }
  std::span<const double> signals() const override { return calls_.ctx_.signals; }
  std::span<double> discrete() override { return calls_.ctx_.discrete; }
  void Changed() override {
    calls_.changed_ = true;
    EvaluateAt(calls_.diagram_, &calls_.ctx_, calls_.ctx_.time, calls_.ctx_.x);
  }
  void Stop(std::string reason) override {
    calls_.stop_requested_ = true;
    calls_.stop_reason_ = std::move(reason);
  }

 private:
  ControlCalls& calls_;
};

bool ControlCalls::Call(double t, double* x, void (RunControl::*call)(ControlPoint&), bool evaluated) {
  if (!evaluated) EvaluateAt(diagram_, &ctx_, t, x);
  changed_ = false;
  Point point(*this);
  (control_->*call)(point);
  if (changed_ && !SettleModes(diagram_, &ctx_))
    throw SimulationError("modes did not settle at t = " + std::to_string(t) + " after the control script's changes");
  return changed_;
}

}  // namespace mechflow::blocks
