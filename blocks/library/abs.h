#pragma once
// Abs: y = |u|, elementwise.
//
//   ports:   input u, output y (both of width `width`); u feeds y directly
//   params:  width (1)
// Events and modes: the corner at u = 0 is a zero crossing with a sign mode
// (y = -u or y = u, frozen inside a step); see piecewise_linear.h.

#include <string>

#include "blocks/library/piecewise_linear.h"

namespace mechflow::blocks {

class AbsBlock : public PiecewiseLinearBlock {
 public:
  AbsBlock(const std::string& name, int width);

 protected:
  double Piece(int mode, double u) const override { return mode == 0 ? -u : u; }
};

}  // namespace mechflow::blocks
