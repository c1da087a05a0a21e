#pragma once
// First-order lag: T y' + y = K u.
//
//   input u (width w), output y (width w), state y; y does not depend on u
//   directly. Step response from y(0) = y0: y = K u + (y0 - K u) exp(-t/T).
//   Parameters: time_constant T [s] > 0, gain K, initial y0.

#include "blocks/block.h"

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
