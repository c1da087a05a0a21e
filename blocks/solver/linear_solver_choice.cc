#include "blocks/solver/linear_solver_choice.h"

#include <algorithm>
#include <string>

#include "blocks/solver/sparsity.h"
#include "mech/errors.h"

namespace mechflow::blocks {

namespace {

// The most nonzeros in one row of the pattern.
int FullestRow(const SparsityPattern& pattern) {
  std::vector<int> count(pattern.n, 0);
  for (const int row : pattern.rows) ++count[row];
  return count.empty() ? 0 : *std::max_element(count.begin(), count.end());
}

}  // namespace

LinearSolverChoice ChooseLinearSolver(const Diagram& diagram, const SolverOptions& options) {
  LinearSolverChoice choice;
  const int n = std::max(1, diagram.num_states());
  const LinearSolverKind kind = options.linear_solver;
  if (kind == LinearSolverKind::kSparse ||
      (kind == LinearSolverKind::kAuto && n >= LinearSolverChoice::kSparseMinStates)) {
    SparsityPattern pattern = DiagramSparsity(diagram);
    // Columns that share a row take different colours, so the fullest row
    // bounds the colours from below: a pattern that cannot qualify is not
    // coloured (a serial chain of 1000 bodies spent 2.8 s colouring its
    // dense pattern, of 2000 bodies 26 s)
    if (kind == LinearSolverKind::kSparse || 4 * FullestRow(pattern) <= n) {
      auto jacobian = std::make_unique<ColouredJacobian>(std::move(pattern));
      if (kind == LinearSolverKind::kSparse || 4 * jacobian->num_colours() <= n) choice.sparse = std::move(jacobian);
    }
  }
  if (!choice.sparse) choice.rate_pairs = DiagramRatePairs(diagram);
  // large mechanisms whose Jacobian is dense: matrix-free (see the header)
  // (not for closed loops: on the slider-crank its inexact solves cost
  // accuracy, 5e-6 against 3e-7 at rtol 1e-8, tests/blocks/solver/second_order_solver_test.cc)
  bool projects = false;
  for (int b = 0; b < diagram.num_blocks(); ++b) projects = projects || diagram.block(b).has_projection();
  choice.krylov = kind == LinearSolverKind::kKrylov ||
                  (kind == LinearSolverKind::kAuto && !choice.sparse && !projects &&
                   n >= LinearSolverChoice::kKrylovMinStates && 4 * static_cast<int>(choice.rate_pairs.size()) >= n);
  if (!choice.krylov && !options.second_order) choice.rate_pairs.clear();
  if (options.jacobian != JacobianKind::kDifferenceQuotient) {
    std::string why = "the krylov linear solver uses no Jacobian";
    const int block = choice.krylov ? -1 : AnalyticJacobian::FindBlock(diagram, &why);
    if (block >= 0) choice.analytic = std::make_unique<AnalyticJacobian>(diagram, block);
    else if (options.jacobian == JacobianKind::kAnalytic)
      throw InputError(AnalyticJacobian::Refusal(why));
  }
  return choice;
}

}  // namespace mechflow::blocks
