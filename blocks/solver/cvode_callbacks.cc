// CVODE's callbacks into the diagram (blocks/solver/cvode_run.h).

#include <cmath>
#include <cstring>
#include <span>
#include <string>

#include <cvode/cvode_ls.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "blocks/framework/algebraic_loop.h"
#include "blocks/framework/evaluation.h"
#include "blocks/solver/cvode_run.h"
#include "blocks/solver/evaluate_at.h"
#include "blocks/solver/run_failure.h"

namespace mechflow::blocks {

int CvodeRun::Rhs(double t, N_Vector y, N_Vector ydot, void* user) {
  return static_cast<CvodeRun*>(user)->EvaluateRhs(t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot));
}

int CvodeRun::EvaluateRhs(double t, double* x, double* xdot) {
  const Diagram& d = diagram_;
  try {
    Context& ctx = ctx_;
    ctx.time = t;
    ctx.x = x;
    ctx.xdot = xdot;
    ++ctx.evaluation;
    ctx.derivatives_follow = true;
    EvaluateOutputs(d, d.dynamics_schedule(), &ctx);
    EvaluateDerivatives(d, &ctx);
    ctx.derivatives_follow = false;
    if (choice_.analytic) {  // where an analytic Jacobian may follow without evaluating again
      rhs_t_ = t;
      std::copy(x, x + rhs_x_.size(), rhs_x_.begin());
      rhs_at_ = ctx.evaluation;
    }
  } catch (const std::exception& e) {
    failures_.set_no_solution(dynamic_cast<const NoSolutionError*>(&e) != nullptr);
    return failures_.Recoverable(e.what());
  }
  if (d.num_states() == 0) xdot[0] = 0.0;  // the placeholder state of a stateless diagram
  for (int i = 0; i < d.num_states(); ++i) {
    if (!std::isfinite(xdot[i])) {
      return failures_.Retry("the derivative of " + DescribeState(d, i) + " is not finite (" +
                             NotFiniteText(xdot[i]) + ") at t = " + std::to_string(t));
    }
  }
  return 0;
}

int CvodeRun::EvaluateAnalyticJacobian(double t, double* x) {
  try {
    const bool current = rhs_at_ != 0 && rhs_at_ == ctx_.evaluation && t == rhs_t_ &&
                         std::memcmp(x, rhs_x_.data(), rhs_x_.size() * sizeof(double)) == 0;
    if (!current) {
      EvaluateAt(diagram_, &ctx_, t, x, /*dynamics_only=*/true);
      ++stats_.jac_rhs_evals;
    }
    ctx_.time = t;
    ctx_.x = x;
    choice_.analytic->Evaluate(&ctx_);
  } catch (const std::logic_error& e) {  // a block's Jacobian outside its own pattern: a bug, never retried
    return failures_.Final(e.what());
  } catch (const std::exception& e) {  // as a right-hand side's failure
    return failures_.Recoverable(e.what());
  }
  return 0;
}

int CvodeRun::DenseJacobian(double t, N_Vector y, N_Vector, SUNMatrix j, void* user, N_Vector, N_Vector,
                            N_Vector) {
  auto* self = static_cast<CvodeRun*>(user);
  if (const int flag = self->EvaluateAnalyticJacobian(t, N_VGetArrayPointer(y)); flag != 0) return flag;
  self->choice_.analytic->ToDense(static_cast<int>(SM_COLUMNS_D(j)), SM_DATA_D(j));
  return 0;
}

int CvodeRun::LinearSystem(double t, N_Vector y, N_Vector fy, SUNMatrix a, sunbooleantype jok,
                           sunbooleantype* jcur, double gamma, void* user, N_Vector, N_Vector, N_Vector) {
  auto* self = static_cast<CvodeRun*>(user);
  ColouredJacobian& jacobian = *self->choice_.sparse;
  const SparsityPattern& pattern = jacobian.pattern();
  if (!jok && self->choice_.analytic) {
    if (const int flag = self->EvaluateAnalyticJacobian(t, N_VGetArrayPointer(y)); flag != 0) return flag;
    try {
      self->choice_.analytic->ToPattern(pattern, self->analytic_values_.data());
    } catch (const std::logic_error& e) {
      return self->failures_.Final(e.what());
    }
    *jcur = SUNTRUE;
  } else if (!jok) {
    // a fresh J at (t, y), with the increments CVODE's dense quotient would take
    void* mem = self->cvode_.get();
    double step = 0.0;
    CVodeGetCurrentStep(mem, &step);
    CVodeGetErrWeights(mem, self->weights_.get());
    double* x = N_VGetArrayPointer(y);
    DifferenceIncrements(pattern.n, x, N_VGetArrayPointer(fy), self->weights_.data(), step,
                         self->increments_.data());
    const int flag = jacobian.Fill(x, N_VGetArrayPointer(fy), self->increments_.data(),
                                   [&](double* xp, double* fp) { return self->EvaluateRhs(t, xp, fp); });
    self->ctx_.x = x;  // the callers' state again, for anything that reads the context next
    // CVODE counts the Jacobian evaluations; the right-hand sides are ours
    self->stats_.jac_rhs_evals += jacobian.num_colours();
    if (flag != 0) return flag;
    *jcur = SUNTRUE;
  } else {
    *jcur = SUNFALSE;
  }
  // A = I - gamma J on the fixed pattern (rewritten each time: a matrix
  // zeroed by anyone else would lose it)
  sunindextype* start = SUNSparseMatrix_IndexPointers(a);
  sunindextype* rows = SUNSparseMatrix_IndexValues(a);
  double* values = SUNSparseMatrix_Data(a);
  const std::vector<double>& j = self->choice_.analytic ? self->analytic_values_ : jacobian.values();
  for (int c = 0; c <= pattern.n; ++c) start[c] = pattern.column_start[c];
  for (int c = 0; c < pattern.n; ++c) {
    for (int k = pattern.column_start[c]; k < pattern.column_start[c + 1]; ++k) {
      rows[k] = pattern.rows[k];
      values[k] = (pattern.rows[k] == c ? 1.0 : 0.0) - gamma * j[k];
    }
  }
  return 0;
}

int CvodeRun::PreconditionRatePairs(double, N_Vector, N_Vector, N_Vector r, N_Vector z, double gamma, double,
                                    int, void* user) {
  // P = I - gamma [rows q' = v]: exact for the pairs, the identity elsewhere
  const auto* self = static_cast<CvodeRun*>(user);
  const double* in = N_VGetArrayPointer(r);
  double* out = N_VGetArrayPointer(z);
  const sunindextype n = N_VGetLength(r);
  for (sunindextype i = 0; i < n; ++i) out[i] = in[i];
  for (const auto& [position, rate] : self->choice_.rate_pairs) out[position] = in[position] + gamma * in[rate];
  return 0;
}

int CvodeRun::Project(double t, N_Vector y, N_Vector correction, double, N_Vector error, void* user) {
  auto* self = static_cast<CvodeRun*>(user);
  const Diagram& d = self->diagram_;
  double* corr = N_VGetArrayPointer(correction);
  double* err = error ? N_VGetArrayPointer(error) : nullptr;
  for (int i = 0; i < d.num_states(); ++i) corr[i] = 0.0;
  // the weights of the step being completed (CVODE sets them at its start)
  void* mem = self->cvode_.get();
  const double* weights =
      CVodeGetErrWeights(mem, self->weights_.get()) == CV_SUCCESS ? self->weights_.data() : nullptr;
  try {
    Context& ctx = self->ctx_;
    ctx.time = t;
    ctx.x = N_VGetArrayPointer(y);
    ++ctx.evaluation;
    for (int b = 0; b < d.num_blocks(); ++b) {
      if (!d.block(b).has_projection()) continue;
      const BlockLayout& layout = d.layout(b);
      const auto n = static_cast<std::size_t>(layout.num_states);
      d.block(b).Project(BlockContext(&ctx, &layout), std::span<double>(corr + layout.first_state, n),
                         err ? std::span<double>(err + layout.first_state, n) : std::span<double>(),
                         weights ? std::span<const double>(weights + layout.first_state, n)
                                 : std::span<const double>());
    }
  } catch (const std::exception& e) {
    return self->failures_.Recoverable(e.what());
  }
  return 0;
}

void CvodeRun::ErrorHandler(int, const char*, const char* function, char* msg, void* user) {
  static_cast<CvodeRun*>(user)->solver_message_ = std::string(function) + ": " + msg;
}

}  // namespace mechflow::blocks
