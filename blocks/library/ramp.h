#pragma once
// Ramp: y = initial for t < start, y = initial + slope (t - start) from then on.
//
//   ports:   no inputs; output y (width 1)
//   params:  slope [unit/s] (1), start [s] (0), initial (0) [unit]
// Events: the corner at t = start is a zero crossing with a mode (see
// switch_at_time.h), so no solver step contains the kink.

#include <string>

#include "blocks/library/switch_at_time.h"

namespace mechflow::blocks {

class RampBlock : public SwitchAtTimeBlock {
 public:
  RampBlock(const std::string& name, double slope, double start, double initial);

 protected:
  void DoCalcOutput(int port, const BlockContext& ctx) const override;

 private:
  double slope_, initial_;
};

}  // namespace mechflow::blocks
