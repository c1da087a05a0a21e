#pragma once
// Clock: y = t [s], the simulation time.
//
//   ports:   no inputs; output y (width 1)
//   params:  none
// No states, no events.

#include <string>

#include "blocks/framework/block.h"

namespace mechflow::blocks {

class ClockBlock : public Block {
 public:
  explicit ClockBlock(const std::string& name);

 protected:
  void DoCalcOutput(int port, const BlockContext& ctx) const override;
};

}  // namespace mechflow::blocks
