#pragma once
// Sum: y = s1 u1 + s2 u2 + ... + sn un, elementwise, s_i = +1 or -1.
//
//   ports:   inputs u1..un (just `u` when n = 1), output y, all of width
//            `width`; every input feeds y directly
//   params:  signs ("++"): one '+' or '-' per input, n = its length;
//            width (1)
// No states, no events.

#include <string>
#include <vector>

#include "blocks/framework/block.h"

namespace mechflow::blocks {

class SumBlock : public Block {
 public:
  // `signs`: one '+' or '-' per input (checked by the factory).
  SumBlock(const std::string& name, const std::string& signs, int width);

 protected:
  void DoCalcOutput(int port, const BlockContext& ctx) const override;

 private:
  std::vector<double> signs_;
};

}  // namespace mechflow::blocks
