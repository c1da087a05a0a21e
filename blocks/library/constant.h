#pragma once
// Constant: y = value.
//
//   ports:   no inputs; output y (width = number of values)
//   params:  value  the output value(s), in the unit of the signal
// No states, no events.

#include <string>
#include <vector>

#include "blocks/framework/block.h"

namespace mechflow::blocks {

class ConstantBlock : public Block {
 public:
  ConstantBlock(const std::string& name, std::vector<double> value);

 protected:
  void DoCalcOutput(int port, const BlockContext& ctx) const override;

 private:
  std::vector<double> value_;
};

}  // namespace mechflow::blocks
