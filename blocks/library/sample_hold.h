#pragma once
// Sample and hold: a periodic zero-order hold.
//
//   ports:   input u, output y (both of width `width`); y does not depend on
//            u at the same instant (u is read only at sample hits), so a
//            sample_hold breaks algebraic loops
//   states:  the held values (discrete, one per element)
//   params:  period [s] (> 0, required), offset [s] (>= 0, default 0),
//            initial (0): y before the first hit, width (1)
//
//   at t_k = offset + k period (k = 0, 1, ...): held = u(t_k)
//   y(t) = held
// The simulator stops the solver exactly at every t_k and reinitialises it
// after the hit, so y jumps at t_k and is constant inside every step. An
// output row at t_k shows the value after the hit.

#include <string>
#include <vector>

#include "blocks/framework/block.h"

namespace mechflow::blocks {

class SampleHoldBlock : public Block {
 public:
  // `initial` has one value per element.
  SampleHoldBlock(const std::string& name, double period, double offset, std::vector<double> initial);

 protected:
  void DoInitialize(const BlockContext& ctx) const override;
  void DoCalcOutput(int port, const BlockContext& ctx) const override;
  void DoSampleHit(const BlockContext& ctx) const override;

 private:
  std::vector<double> initial_;
};

}  // namespace mechflow::blocks
