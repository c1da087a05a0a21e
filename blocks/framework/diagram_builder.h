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

  // Adds a block; names must be unique. Returns a reference valid until Build().
  Block& AddBlock(std::unique_ptr<Block> block, std::string origin = "");

  // Connects output `from` ("block.port", or "block" when it has one output)
  // to input `to` ("block.port", or "block" when it has one input).
  void Connect(std::string_view from, std::string_view to, std::string origin = "");

  // What a run of the diagram must claim before it starts (Diagram::RunClaim).
  void SetRunClaim(RunClaimMaker make) { ThrowIfBuilt("SetRunClaim"); diagram_->run_claim_ = std::move(make); }

  // Checks everything and returns the built diagram.
  std::unique_ptr<Diagram> Build();

 private:
  struct PendingConnection {
    std::string from, to, origin;
  };
  void ThrowIfBuilt(const char* what) const;
  Connection Resolve(const PendingConnection& c) const;
  void CheckInputs(const std::vector<Connection>& resolved) const;
  void LayOut(Diagram* d, const std::vector<Connection>& resolved) const;
  void Schedule(Diagram* d) const;
  static void SplitSchedule(Diagram* d);

  std::unique_ptr<Diagram> diagram_;
  std::vector<PendingConnection> pending_;
};

}  // namespace mechflow::blocks
