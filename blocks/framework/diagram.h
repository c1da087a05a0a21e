#pragma once
// Diagram: a built, immutable block diagram with its schedule.
//
// Produced once by DiagramBuilder::Build(). It owns the blocks and holds
// everything the simulator needs resolved to indices:
//   - the layout of every block in the Context's packed arrays,
//   - the evaluation order of output ports (a topological sort of the
//     direct-feedthrough graph),
//   - the continuous-state layout, the zero-crossing list and the periodic
//     blocks.
// Algebraic loops (strongly connected components of the feedthrough graph)
// are found at build time; each becomes one schedule entry, solved by Newton
// on a few of its signals at every evaluation (see AlgebraicLoop).

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "blocks/framework/algebraic_loop.h"
#include "blocks/framework/block.h"
#include "blocks/framework/block_context.h"

namespace mechflow::blocks {

// A resolved "block.port" signal: where its values sit in Context::signals.
struct SignalRef {
  std::string name;  // "block.port"
  int offset = 0;
  int width = 1;
  // a logged column holds the signal times this: 1 / (SI per unit) when it
  // is logged in a unit other than SI (<log unit="deg">)
  double column_factor = 1.0;
};

struct Connection {
  int from_block = 0, from_port = 0;
  int to_block = 0, to_port = 0;
};

// Made when a Context is prepared for a run and kept by it until it is
// prepared again or ends: a claim on something the diagram's blocks share
// that allows one run at a time (the Lua state of scripting/lua_state.h,
// which refuses a run on another thread meanwhile). Throws when it cannot.
using RunClaimMaker = std::function<std::unique_ptr<BlockScratch>()>;

class Diagram {
 public:
  int num_blocks() const { return static_cast<int>(blocks_.size()); }
  const Block& block(int i) const { return *blocks_.at(i); }
  const BlockLayout& layout(int i) const { return layouts_.at(i); }
  // Where the block was defined ("file:line"), for messages; may be empty.
  const std::string& origin(int i) const { return origins_.at(i); }
  // Index of the named block, or -1.
  int FindBlock(std::string_view name) const;

  int num_signals() const { return num_signals_; }
  int num_states() const { return num_states_; }
  int num_discrete_states() const { return num_discrete_; }
  int num_zero_crossings() const { return num_crossings_; }

  // Output ports in evaluation order; an entry with loop >= 0 is that
  // algebraic loop, solved as a whole.
  const std::vector<OutputNode>& schedule() const { return schedule_; }
  // The schedule split in two, each in schedule order: the entries that the
  // derivatives and zero crossings read (directly or through other outputs),
  // and the rest, which only output rows and watchers read.
  const std::vector<OutputNode>& dynamics_schedule() const { return dynamics_schedule_; }
  const std::vector<OutputNode>& rest_schedule() const { return rest_schedule_; }
  const std::vector<AlgebraicLoop>& loops() const { return loops_; }
  const std::vector<Connection>& connections() const { return connections_; }
  // Blocks with continuous states / zero crossings / a periodic sample time.
  const std::vector<int>& stateful_blocks() const { return stateful_; }
  const std::vector<int>& crossing_blocks() const { return crossing_; }
  const std::vector<int>& periodic_blocks() const { return periodic_; }

  // Empty when runs claim nothing: then several may run at once, one per
  // Context (and thread).
  const RunClaimMaker& run_claim() const { return run_claim_; }

  // Resolves "block.port" (or "block" for a block with one output), or a
  // signal alias (DiagramBuilder::AddSignalAlias; the SignalRef is named as
  // the alias). Block names and port names may hold dots (instance paths,
  // "d[1].fr", sensor ports "s[2].x"): the block is the longest prefix of the
  // reference, up to a '.', that names one, the rest is the port. Throws
  // InputError naming what exists when it does not resolve.
  SignalRef ResolveSignal(std::string_view reference) const;

 private:
  friend class DiagramBuilder;
  Diagram() = default;
  // The block that `reference` starts with (see ResolveSignal), its port part
  // in *port ("" for the block alone); -1 when no prefix names a block, with
  // *port then what follows the last '.'. As many lookups as the reference
  // has dots, whatever the number of blocks.
  int FindBlockOf(std::string_view reference, std::string_view* port) const;
  // The output port `reference` names: its block and port. Throws InputError
  // ("signal 'REF': ...") naming what exists when it names none.
  std::pair<int, int> FindOutput(std::string_view reference) const;

  std::vector<std::unique_ptr<Block>> blocks_;
  std::vector<std::string> origins_;
  std::map<std::string, int, std::less<>> block_index_;  // name -> block, for FindBlock
  // signal alias -> the "block.port" it stands for (chains of aliases followed)
  std::map<std::string, std::string, std::less<>> aliases_;
  std::vector<BlockLayout> layouts_;
  std::vector<Connection> connections_;
  std::vector<OutputNode> schedule_, dynamics_schedule_, rest_schedule_;
  std::vector<AlgebraicLoop> loops_;
  // (output slot, input copy slot) of each value a block feeds to itself
  // directly; the copies are extra signals after the outputs'
  std::vector<std::pair<int, int>> input_copies_;
  std::vector<int> stateful_, crossing_, periodic_;
  int num_signals_ = 0, num_states_ = 0, num_discrete_ = 0, num_crossings_ = 0;
  RunClaimMaker run_claim_;
};

}  // namespace mechflow::blocks
