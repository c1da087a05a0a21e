#pragma once
// The "identifier" block: the current value of one identifier as a signal.
//
//   +------------+
//   | identifier | ---> y
//   +------------+
//
//   output:  y (width 1), no inputs
//   params:  identifier (text, required) the identifier's name
//
// This is how a value that a control script sets (sim:set) drives blocks and
// mechanism inputs: a sampled controller sets `torque`, an identifier block
// reads it, a connection feeds it to the mechanism's input port. The value
// is a discrete state, so it changes only between integrator steps (the
// integrator is re-initialised after each change) and every run starts from
// the value the diagram was loaded with.

#include "blocks/framework/block.h"
#include "blocks/framework/block_factory.h"

namespace mechflow::scripting {

class IdentifierTable;

class IdentifierBlock final : public blocks::Block {
 public:
  // `identifier` is the index in the table, `initial` its value at load.
  IdentifierBlock(const std::string& name, int identifier, double initial);
  int identifier() const { return identifier_; }

 protected:
  void DoInitialize(const blocks::BlockContext& ctx) const override { ctx.discrete()[0] = initial_; }
  void DoCalcOutput(int, const blocks::BlockContext& ctx) const override { ctx.output(0)[0] = ctx.discrete()[0]; }

 private:
  int identifier_;
  double initial_;
};

// Registers "identifier"; `identifiers` must be evaluated and outlive the registry.
void RegisterIdentifierBlock(blocks::BlockRegistry* registry, const IdentifierTable* identifiers);

}  // namespace mechflow::scripting
