#pragma once
// Blocks that only consume signals.
//
//   recorder     inputs u (or u1..un), no outputs. The loader logs whatever
//                drives its inputs, as one plot panel named after the recorder.
//   sample_hold  periodic zero-order hold: at t = offset + k period it samples
//                u into a discrete state; y shows the held value (no direct
//                feedthrough). Before the first sample y = initial.

#include "blocks/block.h"

namespace mechflow::blocks {

class RecorderBlock : public Block {
 public:
  RecorderBlock(const std::string& name, int num_inputs, int width);

 protected:
  void DoCalcOutput(int, const BlockContext&) const override {}
};

class SampleHoldBlock : public Block {
 public:
  SampleHoldBlock(const std::string& name, double period, double offset, std::vector<double> initial);

 protected:
  void DoInitialize(const BlockContext& ctx) const override;
  void DoCalcOutput(int port, const BlockContext& ctx) const override;
  void DoSampleHit(const BlockContext& ctx) const override;

 private:
  std::vector<double> initial_;
};

}  // namespace mechflow::blocks
