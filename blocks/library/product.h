#pragma once
// Product: y = 1 op1 u1 op2 u2 ... opn un, elementwise, op_i = '*' or '/'.
//
//   ports:   inputs u1..un (just `u` when n = 1), output y, all of width
//            `width`; every input feeds y directly
//   params:  inputs  n, when `operations` is not given (2: y = u1 u2)
//            operations  one '*' or '/' per input, e.g. "**/" for u1 u2 / u3
//                        (n = its length; "/" alone gives 1/u)
//            width (1)
// Units: the product of the inputs' units.
// A zero divisor during the run is a SimulationError naming the block and
// input (the solver may retry a smaller step first).

#include <string>

#include "blocks/framework/block.h"

namespace mechflow::blocks {

class ProductBlock : public Block {
 public:
  // `operations`: one '*' or '/' per input (checked by the factory).
  ProductBlock(const std::string& name, const std::string& operations, int width);

 protected:
  void DoCalcOutput(int port, const BlockContext& ctx) const override;

 private:
  std::string operations_;
};

}  // namespace mechflow::blocks
