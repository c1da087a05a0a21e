#pragma once
// Saturation: y = lower for u < lower, u in [lower, upper], upper for u > upper,
// elementwise.
//
//   ports:   input u, output y (both of width `width`); u feeds y directly
//   params:  lower, upper (required, lower < upper) [unit of u], width (1)
// Events and modes: modes below / linear / above, switched by zero crossings
// of u - lower and u - upper; y is computed from the frozen mode inside a
// step, and UpdateModes re-classifies from u after every event; see
// piecewise_linear.h.

#include <string>

#include "blocks/library/piecewise_linear.h"

namespace mechflow::blocks {

class SaturationBlock : public PiecewiseLinearBlock {
 public:
  SaturationBlock(const std::string& name, double lower, double upper, int width);

 protected:
  double Piece(int mode, double u) const override;

 private:
  double lower_, upper_;
};

}  // namespace mechflow::blocks
