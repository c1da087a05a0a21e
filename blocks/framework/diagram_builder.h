#pragma once
// DiagramBuilder: collects blocks and connections, checks them, and builds a
// Diagram. Single use: after Build() the builder is empty and refuses work.
//
// Errors are InputError and name both ends of the faulty connection, with the
// origin ("file:line") given when the item was added:
//   - a connection to a block or port that does not exist (valid ones listed),
//   - a width mismatch,
//   - an input driven twice (both drivers named),
//   - an unconnected input,
//   - an algebraic loop (the whole cycle of block.port hops, and a hint).

#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "blocks/framework/diagram.h"

namespace mechflow::blocks {

class DiagramBuilder {
 public:
  DiagramBuilder();
  ~DiagramBuilder();

  // Adds a block; names must be unique and may be instance paths ("d[1].fr":
  // parts joined by '.', none empty). Returns a reference valid until Build().
  Block& AddBlock(std::unique_ptr<Block> block, std::string origin = "");

  // Connects output `from` ("block.port", or "block" when it has one output)
  // to input `to` ("block.port", or "block" when it has one input).
  void Connect(std::string_view from, std::string_view to, std::string origin = "");

  // Another name for an output: `alias` ("d[1].F", a subsystem's output)
  // stands for `target` ("d[1].fr.F", or another alias) wherever an output
  // is named -- ResolveSignal, a connection's `from`. Build() refuses (naming
  // `origin`) a target that is no output, a circle of aliases, and an alias
  // that is already the name of an output.
  void AddSignalAlias(std::string_view alias, std::string_view target, std::string origin = "");

  // What a run of the diagram must claim before it starts (Diagram::RunClaim).
  void SetRunClaim(RunClaimMaker make) { ThrowIfBuilt("SetRunClaim"); diagram_->run_claim_ = std::move(make); }

  // Checks everything and returns the built diagram.
  std::unique_ptr<Diagram> Build();

 private:
  struct PendingConnection {
    std::string from, to, origin;
  };
  struct PendingAlias {
    std::string target, origin;
  };
  void ThrowIfBuilt(const char* what) const;
  void ResolveAliases();
  Connection Resolve(const PendingConnection& c) const;
  void CheckInputs(const std::vector<Connection>& resolved) const;
  void LayOut(Diagram* d, const std::vector<Connection>& resolved) const;
  void Schedule(Diagram* d) const;
  static void SplitSchedule(Diagram* d);

  std::unique_ptr<Diagram> diagram_;
  std::vector<PendingConnection> pending_;
  std::map<std::string, PendingAlias, std::less<>> pending_aliases_;
  std::vector<std::string> alias_order_;  // as added, so the first faulty one is reported
};

}  // namespace mechflow::blocks
