#pragma once
// Recorder: a sink. It computes nothing; the loader logs the signals that
// drive its inputs, as one plot panel named after the recorder.
//
//   ports:   inputs u1..un (just `u` when n = 1), each of width `width`;
//            no outputs
//   params:  inputs n (1), width (1)
// No states, no events.

#include <string>

#include "blocks/framework/block.h"

namespace mechflow::blocks {

class RecorderBlock : public Block {
 public:
  RecorderBlock(const std::string& name, int num_inputs, int width);

 protected:
  // never called: there are no outputs
  void DoCalcOutput(int, const BlockContext&) const override {}
};

}  // namespace mechflow::blocks
