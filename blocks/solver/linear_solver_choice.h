#pragma once
// Which linear solver the Newton iterations of a run use, chosen once per
// diagram (the Jacobian's structure is the diagram's). Three linear solvers:
//   dense:  CVODE's dense matrix and difference-quotient Jacobian (n
//           right-hand sides per Jacobian, O(n^3) factorisation); with rate
//           pairs (q' = v) the positions are eliminated before the LU
//           (blocks/solver/second_order_solver.h);
//   sparse: the diagram's structural pattern (blocks/solver/sparsity.h), filled by
//           coloured difference quotients (one right-hand side per colour,
//           blocks/solver/coloured_jacobian.h) into a compressed-column matrix that
//           KLU factors. The Newton matrix I - gamma J is formed by the
//           simulator (CVodeSetLinSysFn): CVODE's own construction of it for
//           a sparse matrix costs O(n^2) (in SUNDIALS 6.4 it took 91 % of a
//           29 s run of the P3 chain at N = 1000);
//   krylov: GMRES (SPGMR), matrix-free: each iteration one right-hand side
//           for J v by a difference quotient, O(n) for a mechanism; the
//           preconditioner solves the rows q' = v exactly (identity
//           elsewhere). No Jacobian, no factorisation: for large mechanisms
//           whose Jacobian is dense (a long serial chain: every acceleration
//           reads every coordinate), where dense costs n^2 per Jacobian and
//           n^3 per factorisation.
// Dense and sparse take the blocks' analytic Jacobian instead of difference
// quotients when the diagram has one (blocks/solver/analytic_jacobian.h; a sliding
// mechanism, mech/sliding_jacobian.h): no right-hand sides per Jacobian.
// kAuto picks sparse when the diagram has at least kSparseMinStates states and
// its pattern needs at most a quarter as many colours as states (so a fill
// costs at most n/4 right-hand sides); otherwise krylov when it has at least
// kKrylovMinStates states of which rate pairs are at least a quarter and no
// block projects (closed loops, quaternions); dense otherwise. On the P4
// chain (bench/README.md) krylov and dense break even at 50 bodies (100
// states), krylov is 2x faster at 200 and grows as N^1.2 up to 2000
// bodies. Measured on the P3 chain (CPU time): sparse wins already at 20
// states (0.07 s against 0.14 s), by 1.2x at 30 (bench_friction, P3 N = 10),
// 1.6x at 90 and 7x at 200 (1.4 s against 10.3 s). No example diagram
// changes solver at this threshold (it was 100 until every other cost of a
// small run had come down).

#include <memory>
#include <utility>
#include <vector>

#include "blocks/framework/diagram.h"
#include "blocks/solver/analytic_jacobian.h"
#include "blocks/solver/coloured_jacobian.h"
#include "blocks/solver/solver_options.h"

namespace mechflow::blocks {

struct LinearSolverChoice {
  // Smallest state count for which kAuto considers a sparse Jacobian.
  static constexpr int kSparseMinStates = 20;
  // Smallest state count for which kAuto picks the Krylov solver.
  static constexpr int kKrylovMinStates = 200;

  std::unique_ptr<ColouredJacobian> sparse;       // sparse runs only
  std::vector<std::pair<int, int>> rate_pairs;    // dense: eliminated from the Newton systems; Krylov: preconditioner
  bool krylov = false;                            // GMRES, matrix-free
  std::unique_ptr<AnalyticJacobian> analytic;     // when the run uses one
};

// Throws InputError when options.jacobian is kAnalytic and the diagram has
// no analytic Jacobian (or the run is krylov, which uses none).
LinearSolverChoice ChooseLinearSolver(const Diagram& diagram, const SolverOptions& options);

}  // namespace mechflow::blocks
