#include "blocks/solver/cvode_run.h"

#include <algorithm>
#include <cmath>

#include <cvode/cvode_ls.h>
#include <cvode/cvode_proj.h>

#include "blocks/solver/run_failure.h"

namespace mechflow::blocks {

namespace {

// GMRES iterations per linear solve, without restarts (CVODE's default):
// CVODE takes a solve that has not converged by then as a failure and
// retries with a smaller step
constexpr int kKrylovDimension = 5;

}  // namespace

CvodeRun::CvodeRun(const Diagram& diagram, Context* ctx, const SolverOptions& options,
                   const LinearSolverChoice& choice, SolverStats* stats, CallbackFailures* failures)
    : n_(std::max(1, diagram.num_states())),
      step_end(n_, sundials_),
      watch(n_, sundials_),
      check(n_, sundials_),
      search(n_, sundials_),
      polynomial(n_, sundials_),
      diagram_(diagram),
      ctx_(*ctx),
      options_(options),
      choice_(choice),
      stats_(*stats),
      failures_(*failures),
      y_(n_, sundials_),
      weights_(n_, sundials_),
      cvode_(sundials_) {
  std::fill(y_.data(), y_.data() + n_, 0.0);
  // one of Krylov, sparse, second-order (dense, with rate pairs) and dense
  if (choice_.krylov) {
    krylov_ = std::make_unique<sundials::KrylovSolver>(y_, kKrylovDimension, sundials_);
  } else if (choice_.sparse) {
    sparse_ = std::make_unique<sundials::SparseSolver>(y_, choice_.sparse->pattern(), sundials_);
    increments_.assign(n_, 0.0);
    if (choice_.analytic) analytic_values_.assign(choice_.sparse->pattern().nonzeros(), 0.0);
  } else if (!choice_.rate_pairs.empty()) {
    second_order_ = std::make_unique<SecondOrderSolver>(y_, choice_.rate_pairs, [this] {
      double gamma = 0.0;  // called by CVODE: no exception may pass
      return CVodeGetCurrentGamma(cvode_.get(), &gamma) < 0 ? std::nan("") : gamma;
    }, sundials_);
  } else {
    dense_ = std::make_unique<sundials::DenseSolver>(y_, sundials_);
  }
  rhs_x_.assign(choice_.analytic ? n_ : 0, 0.0);
  if (choice_.sparse) {
    stats_.sparse = true;
    stats_.colours = choice_.sparse->num_colours();
    stats_.nonzeros = choice_.sparse->pattern().nonzeros();
  }
  stats_.krylov = choice_.krylov;
  stats_.analytic_jacobian = choice_.analytic != nullptr;
  stats_.newton_size = newton_size();
}

CvodeRun::~CvodeRun() = default;

void CvodeRun::Start(double t0) {
  using sundials::Check;
  void* mem = cvode_.get();
  Check(CVodeInit(mem, &CvodeRun::Rhs, t0, y_.get()), "CVodeInit");
  Check(CVodeSetUserData(mem, this), "CVodeSetUserData");
  Check(CVodeSetErrHandlerFn(mem, &CvodeRun::ErrorHandler, this), "CVodeSetErrHandlerFn");
  Check(CVodeSStolerances(mem, options_.rtol, options_.atol), "CVodeSStolerances");
  SUNMatrix matrix = krylov_ ? nullptr : sparse_ ? sparse_->matrix() : second_order_ ? second_order_->matrix()
                                                                                     : dense_->matrix();
  SUNLinearSolver solver = krylov_         ? krylov_->solver()
                           : sparse_       ? sparse_->solver()
                           : second_order_ ? second_order_->solver()
                                           : dense_->solver();
  Check(CVodeSetLinearSolver(mem, solver, matrix), "CVodeSetLinearSolver");
  if (sparse_) Check(CVodeSetLinSysFn(mem, &CvodeRun::LinearSystem), "CVodeSetLinSysFn");
  else if (choice_.analytic) Check(CVodeSetJacFn(mem, &CvodeRun::DenseJacobian), "CVodeSetJacFn");
  if (krylov_) Check(CVodeSetPreconditioner(mem, nullptr, &CvodeRun::PreconditionRatePairs), "CVodeSetPreconditioner");
  linear_solver_attached_ = true;
  Check(CVodeSetMaxNumSteps(mem, options_.max_steps), "CVodeSetMaxNumSteps");
  if (options_.max_step > 0.0) Check(CVodeSetMaxStep(mem, options_.max_step), "CVodeSetMaxStep");
  if (options_.initial_step > 0.0) Check(CVodeSetInitStep(mem, options_.initial_step), "CVodeSetInitStep");
  // Below this step t + h == t (or nearly): steps would not advance time,
  // and CVODE, merely warning, would go on writing rows of a frozen state.
  Check(CVodeSetMinStep(mem, MinimumStep(options_.t_start, options_.t_end)), "CVodeSetMinStep");
  // projection needs the linear solver attached first (CVODE's rule)
  for (int b = 0; b < diagram_.num_blocks(); ++b) {
    if (!diagram_.block(b).has_projection()) continue;
    Check(CVodeSetProjFn(mem, &CvodeRun::Project), "CVodeSetProjFn");
    projection_attached_ = true;
    break;
  }
}

void CvodeRun::Reinitialize(double t) {
  AccumulateStats();
  sundials::Check(CVodeReInit(cvode_.get(), t, y_.get()), "CVodeReInit");
  ++stats_.reinits;
}

void CvodeRun::StateAt(double t, N_Vector out) const {
  sundials::Check(CVodeGetDky(cvode_.get(), t, 0, out), "CVodeGetDky");
}

void CvodeRun::AccumulateStats() {
  void* mem = cvode_.get();
  long v = 0;
  auto add = [&](int flag, long* total) {
    if (flag >= 0) *total += v;
  };
  add(CVodeGetNumSteps(mem, &v), &stats_.steps);
  add(CVodeGetNumRhsEvals(mem, &v), &stats_.rhs_evals);
  if (linear_solver_attached_) {  // otherwise CVLS would complain on stderr
    add(CVodeGetNumLinRhsEvals(mem, &v), &stats_.jac_rhs_evals);
    add(CVodeGetNumJacEvals(mem, &v), &stats_.jac_evals);
    add(CVodeGetNumLinIters(mem, &v), &stats_.linear_iters);
  }
  add(CVodeGetNumNonlinSolvIters(mem, &v), &stats_.newton_iters);
  add(CVodeGetNumNonlinSolvConvFails(mem, &v), &stats_.newton_failures);
  add(CVodeGetNumErrTestFails(mem, &v), &stats_.error_test_failures);
  add(CVodeGetNumGEvals(mem, &v), &stats_.root_evals);
  if (projection_attached_) {  // likewise for the projection's counters
    add(CVodeGetNumProjEvals(mem, &v), &stats_.projections);
    add(CVodeGetNumProjFails(mem, &v), &stats_.projection_failures);
  }
}

}  // namespace mechflow::blocks
