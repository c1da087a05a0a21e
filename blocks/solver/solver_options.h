#pragma once
// The settings of one simulator run and the counters it reports.

#include <string>
#include <vector>

namespace mechflow::blocks {

enum class LinearSolverKind { kAuto, kDense, kSparse, kKrylov };
// Where the Newton matrices' Jacobian comes from: kAuto takes the analytic
// one when the diagram has it (blocks/solver/analytic_jacobian.h), difference
// quotients otherwise; kAnalytic refuses a diagram without it.
enum class JacobianKind { kAuto, kAnalytic, kDifferenceQuotient };

struct SolverOptions {
  double t_start = 0.0;      // [s]
  double t_end = 1.0;        // [s], > t_start
  double rtol = 1e-6;        // relative tolerance, > 0
  double atol = 1e-8;        // absolute tolerance, > 0
  double max_step = 0.0;     // [s], 0: no limit
  double initial_step = 0.0; // [s], 0: CVODE's own estimate
  long max_steps = 500000;   // steps allowed between two output times
  double output_interval = 0.0;  // [s], 0: (t_end - t_start) / 1000
  // Rows at exactly these instants instead of the interval's grid (to compare
  // with measured samples): increasing, within [t_start, t_end].
  std::vector<double> output_times;
  LinearSolverKind linear_solver = LinearSolverKind::kAuto;
  // Dense runs of diagrams with rate pairs (x_q' = x_v, Block::rate_pairs)
  // eliminate the positions from each Newton system
  // (blocks/solver/second_order_solver.h); false solves the whole system, as
  // before (for comparisons).
  bool second_order = true;
  JacobianKind jacobian = JacobianKind::kAuto;

  // Empty when usable, otherwise what is wrong (e.g. "rtol must be > 0").
  std::string Problem() const;
  std::string OutputTimesProblem() const;  // the part of Problem about output_times
};

// Solver counters accumulated over the whole run (across re-initialisations).
struct SolverStats {
  long steps = 0;
  long rhs_evals = 0;        // by the integrator
  long jac_rhs_evals = 0;    // by the difference-quotient Jacobian; with the analytic one, the
                             // output evaluations it needed (at a state no right-hand side had just seen)
  long jac_evals = 0;
  long newton_iters = 0;
  long linear_iters = 0;     // Krylov iterations (0 with direct solvers)
  long newton_failures = 0;  // nonlinear convergence failures
  long error_test_failures = 0;
  long root_evals = 0;
  long events = 0;           // zero crossings handled
  long sample_hits = 0;
  long reinits = 0;
  long restarts = 0;         // after repeated error-test or convergence failures (a re-initialisation too)
  long projections = 0;          // projection calls (0 unless a block declares one)
  long projection_failures = 0;  // failed projections (each retries its step smaller)
  bool sparse = false;           // sparse Jacobian and KLU (otherwise dense or Krylov)
  bool krylov = false;           // GMRES with difference-quotient products J v
  bool analytic_jacobian = false;  // the blocks' exact Jacobian (blocks/solver/analytic_jacobian.h)
  int newton_size = 0;           // unknowns of each Newton system solved (fewer than states with rate pairs)
  int colours = 0;               // sparse: column groups, right-hand sides per Jacobian
  long nonzeros = 0;             // sparse: entries of the structural pattern
};

}  // namespace mechflow::blocks
