#pragma once
// Gain: y = k u, elementwise.
//
//   ports:   input u, output y (both of width `width`); u feeds y directly
//   params:  k (required) [unit of y / unit of u], width (1)
// No states, no events.

#include <string>

#include "blocks/framework/block.h"

namespace mechflow::blocks {

class GainBlock : public Block {
 public:
  GainBlock(const std::string& name, double k, int width);

 protected:
  void DoCalcOutput(int port, const BlockContext& ctx) const override;

 private:
  double k_;
};

}  // namespace mechflow::blocks
