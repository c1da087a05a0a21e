#pragma once
// Sine: y = bias + amplitude sin(2 pi frequency t + phase).
//
//   ports:   no inputs; output y (width 1)
//   params:  amplitude (1) [unit], frequency [Hz] (1), phase [rad] (0),
//            bias (0) [unit]
// No states, no events.

#include <numbers>
#include <string>

#include "blocks/framework/block.h"

namespace mechflow::blocks {

class SineBlock : public Block {
 public:
  SineBlock(const std::string& name, double amplitude, double frequency, double phase, double bias);

 protected:
  void DoCalcOutput(int port, const BlockContext& ctx) const override;
  double OwnTimeScale() const override { return 2.0 * std::numbers::pi / std::abs(omega_); }  // the period

 private:
  double amplitude_;
  double omega_;  // 2 pi frequency [rad/s]
  double phase_, bias_;
};

}  // namespace mechflow::blocks
