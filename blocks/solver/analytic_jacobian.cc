#include "blocks/solver/analytic_jacobian.h"

#include <algorithm>
#include <stdexcept>

namespace mechflow::blocks {

int AnalyticJacobian::FindBlock(const Diagram& d, std::string* why) {
  int found = -1;
  for (int b = 0; b < d.num_blocks(); ++b) {
    if (d.layout(b).num_states == 0) continue;
    if (found >= 0) {
      *why = "blocks '" + d.block(found).name() + "' and '" + d.block(b).name() + "' both have states";
      return -1;
    }
    found = b;
  }
  if (found < 0) {
    *why = "the diagram has no continuous states";
    return -1;
  }
  const std::string unavailable = d.block(found).StateJacobianUnavailable();
  if (!unavailable.empty()) {
    *why = unavailable;
    return -1;
  }
  if (InputsReadStates(d, found)) {
    *why = "an input of '" + d.block(found).name() + "' reads its states (feedback through other blocks)";
    return -1;
  }
  return found;
}

void AnalyticJacobian::Evaluate(Context* ctx) {
  diagram_.block(block_).CalcStateJacobian(BlockContext(ctx, &diagram_.layout(block_)), &entries_);
}

void AnalyticJacobian::ToPattern(const SparsityPattern& pattern, double* values) const {
  std::fill(values, values + pattern.nonzeros(), 0.0);
  const int first = diagram_.layout(block_).first_state;
  for (const auto& [row, column, value] : entries_) {
    const int i = first + row, j = first + column;
    const auto begin = pattern.rows.begin() + pattern.column_start[j];
    const auto end = pattern.rows.begin() + pattern.column_start[j + 1];
    const auto at = std::lower_bound(begin, end, i);
    if (at == end || *at != i)
      throw std::logic_error("analytic Jacobian: entry (" + std::to_string(i) + ", " + std::to_string(j) +
                             ") of block '" + diagram_.block(block_).name() + "' is outside the structural pattern");
    values[at - pattern.rows.begin()] += value;
  }
}

void AnalyticJacobian::ToDense(int n, double* columns) const {
  std::fill(columns, columns + static_cast<long>(n) * n, 0.0);
  const int first = diagram_.layout(block_).first_state;
  for (const auto& [row, column, value] : entries_)
    columns[static_cast<long>(first + column) * n + first + row] += value;
}

}  // namespace mechflow::blocks
