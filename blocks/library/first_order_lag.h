#pragma once
// First-order lag: T y' + y = K u, elementwise.
//
//   ports:   input u, output y (both of width w); y is the state, so u does
//            not feed y directly (the lag breaks algebraic loops)
//   states:  y (w continuous)
//   params:  time_constant T [s] (> 0, required), gain K (1) [unit of y /
//            unit of u], initial y(t_start) (0; one value or one per
//            element), width w (1)
// Step response from y(0) = y0 to a constant u: y = K u + (y0 - K u) exp(-t/T).
// No events.

#include "blocks/framework/block.h"

namespace mechflow::blocks {

class FirstOrderLagBlock : public Block {
 public:
  FirstOrderLagBlock(const std::string& name, double time_constant, double gain, std::vector<double> initial);

 protected:
  void DoInitialize(const BlockContext& ctx) const override;
  void DoCalcOutput(int port, const BlockContext& ctx) const override;
  void DoCalcDerivatives(const BlockContext& ctx) const override;

 private:
  double time_constant_, gain_;
  std::vector<double> initial_;
};

}  // namespace mechflow::blocks
