#pragma once
// Held input: a value set from outside the diagram, held between the times
// it is set (a diagram's top-level <input>, which a co-simulation drives).
//
//   +-------+
//   | input | ---> y
//   +-------+
//
//   output:  y (width 1), no inputs
// The value is a discrete state, so it changes only between integrator
// steps (whoever sets it restarts the integrator: Simulator::RestartHere),
// and every run starts from `start`. Not a block type of <blocks>: made by
// the loader from <input>.

#include <string>

#include "blocks/framework/block.h"

namespace mechflow::blocks {

class HeldInputBlock final : public Block {
 public:
  HeldInputBlock(const std::string& name, double start);

 protected:
  void DoInitialize(const BlockContext& ctx) const override { ctx.discrete()[0] = start_; }
  void DoCalcOutput(int, const BlockContext& ctx) const override { ctx.output(0)[0] = ctx.discrete()[0]; }

 private:
  double start_;
};

}  // namespace mechflow::blocks
