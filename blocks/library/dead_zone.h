#pragma once
// Dead zone: y = u - start for u < start, 0 in [start, end], u - end for u > end,
// elementwise.
//
//   ports:   input u, output y (both of width `width`); u feeds y directly
//   params:  start, end (required, start < end) [unit of u], width (1)
// Events and modes: modes below / zone / above, switched by zero crossings of
// u - start and u - end; y is computed from the frozen mode inside a step;
// see piecewise_linear.h.

#include <string>

#include "blocks/library/piecewise_linear.h"

namespace mechflow::blocks {

class DeadZoneBlock : public PiecewiseLinearBlock {
 public:
  DeadZoneBlock(const std::string& name, double start, double end, int width);

 protected:
  double Piece(int mode, double u) const override;

 private:
  double start_, end_;
};

}  // namespace mechflow::blocks
