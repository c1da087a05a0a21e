#pragma once
// AnalyticJacobian: the diagram's Jacobian df/dx from the blocks' own exact
// derivatives (Block::CalcStateJacobian), instead of difference quotients
// (one block evaluation per state column, the cost of large friction chains).
//
// It applies when the diagram has exactly one block with continuous states,
// that block computes its Jacobian, and none of its inputs reads a state
// (through any chain of signals): df/dx is then the block's own, with its
// inputs held. Feedback through other blocks would add products of their
// Jacobians; those diagrams keep difference quotients.

#include <string>
#include <vector>

#include "blocks/framework/block_context.h"
#include "blocks/framework/diagram.h"
#include "blocks/solver/sparsity.h"

namespace mechflow::blocks {

class AnalyticJacobian {
 public:
  // The block whose Jacobian is the diagram's, or -1 with *why set to a
  // sentence saying why there is none.
  static int FindBlock(const Diagram& diagram, std::string* why);
  // The message refusing jacobian="analytic" for that reason.
  static std::string Refusal(const std::string& why) {
    return "solver jacobian=\"analytic\": " + why + "; use jacobian=\"auto\" or \"difference\"";
  }

  AnalyticJacobian(const Diagram& diagram, int block) : diagram_(diagram), block_(block) {}

  // The block's entries at the context's time and state, where the
  // diagram's outputs were just computed.
  void Evaluate(Context* ctx);
  // Into the values of a compressed-column `pattern` (zero elsewhere);
  // std::logic_error for an entry outside it (a block whose declared
  // sparsity misses what it reads).
  void ToPattern(const SparsityPattern& pattern, double* values) const;
  // Into an n x n column-major matrix, zeroed first.
  void ToDense(int n, double* columns) const;

 private:
  const Diagram& diagram_;
  int block_;
  std::vector<JacobianEntry> entries_;  // block-local
};

}  // namespace mechflow::blocks
