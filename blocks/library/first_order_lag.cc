#include "blocks/library/first_order_lag.h"

#include <algorithm>

namespace mechflow::blocks {

FirstOrderLagBlock::FirstOrderLagBlock(const std::string& name, double time_constant, double gain,
                                       std::vector<double> initial)
    : Block("first_order_lag", name), time_constant_(time_constant), gain_(gain), initial_(std::move(initial)) {
  const int w = static_cast<int>(initial_.size());
  DeclareInputPort("u", w);
  DeclareOutputPort("y", w);
  DeclareNoFeedthrough();
  DeclareContinuousStates(w, "y");
}

void FirstOrderLagBlock::DoInitialize(const BlockContext& ctx) const {
  std::copy(initial_.begin(), initial_.end(), ctx.state().begin());
}

void FirstOrderLagBlock::DoCalcOutput(int, const BlockContext& ctx) const {
  const auto y = ctx.state();
  std::copy(y.begin(), y.end(), ctx.output(0).begin());
}

void FirstOrderLagBlock::DoCalcDerivatives(const BlockContext& ctx) const {
  const auto u = ctx.input(0);
  const auto y = ctx.state();
  const auto ydot = ctx.derivative();
  for (size_t i = 0; i < y.size(); ++i) ydot[i] = (gain_ * u[i] - y[i]) / time_constant_;
}

}  // namespace mechflow::blocks
