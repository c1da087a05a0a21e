#pragma once
// CvodeRun: the SUNDIALS objects of one simulator run (state vector, linear
// solver, CVODE's memory) and CVODE's callbacks into the diagram: the
// right-hand side, the Newton systems' Jacobian (dense analytic, or the
// sparse I - gamma J), the Krylov preconditioner, the blocks' projection.
//
// Nothing in the right-hand side allocates, parses or looks a name up; a
// callback that fails keeps its reason in CallbackFailures and returns the
// flag CVODE expects (recoverable at first).

#include <cstdint>
#include <string>
#include <vector>

#include "blocks/framework/block_context.h"
#include "blocks/framework/diagram.h"
#include "blocks/solver/callback_failures.h"
#include "blocks/solver/linear_solver_choice.h"
#include "blocks/solver/second_order_solver.h"
#include "blocks/solver/solver_options.h"
#include "blocks/solver/step_polynomial.h"
#include "blocks/solver/sundials.h"

#include <sundials/sundials_matrix.h>
#include <sundials/sundials_nvector.h>

namespace mechflow::blocks {

class CvodeRun {
  // first: the vectors below are made in their context
  const sunindextype n_;  // states
  sundials::Context sundials_;

 public:
  // The objects for the diagram's states (one placeholder state when it has
  // none) and the linear solver `choice` names (not owned; nor are the
  // others, which must outlive this).
  CvodeRun(const Diagram& diagram, Context* ctx, const SolverOptions& options, const LinearSolverChoice& choice,
           SolverStats* stats, CallbackFailures* failures);
  ~CvodeRun();
  CvodeRun(const CvodeRun&) = delete;
  CvodeRun& operator=(const CvodeRun&) = delete;

  // CVodeInit at (t0, y()) with the tolerances, step limits, linear solver
  // and (when a block declares one) projection attached.
  void Start(double t0);
  // CVodeReInit at (t, y()), after adding the counters of the last start.
  void Reinitialize(double t);
  // Adds CVODE's counters since it last started to the stats.
  void AccumulateStats();

  void* mem() const { return cvode_.get(); }
  sunindextype n() const { return n_; }
  const sundials::Context& sundials_context() const { return sundials_; }
  // The state CVODE starts (and restarts) from.
  double* y() const { return y_.data(); }
  // Unknowns of each Newton system (fewer than states when rate pairs are eliminated).
  int newton_size() const { return second_order_ ? second_order_->reduced_size() : static_cast<int>(n_); }
  // The state at t on the last step's interpolant, into out (Check'd CVodeGetDky).
  void StateAt(double t, N_Vector out) const;
  // The last message of CVODE's error handler (or the simulator's own).
  std::string& solver_message() { return solver_message_; }

  // Scratch states: where a step ends (CVode's output), on a step the reports
  // watch, at a check inside a step, at a probe or trial of the crossing
  // search; and the polynomial of a step with several rows.
  sundials::Vector step_end, watch, check, search;
  StepPolynomial polynomial;

 private:
  static int Rhs(double t, N_Vector y, N_Vector ydot, void* self);
  static int LinearSystem(double t, N_Vector y, N_Vector fy, SUNMatrix A, sunbooleantype jok,
                          sunbooleantype* jcur, double gamma, void* self, N_Vector, N_Vector, N_Vector);
  static int DenseJacobian(double t, N_Vector y, N_Vector fy, SUNMatrix j, void* self, N_Vector, N_Vector,
                           N_Vector);
  static int PreconditionRatePairs(double t, N_Vector y, N_Vector fy, N_Vector r, N_Vector z, double gamma,
                                   double delta, int side, void* self);
  static int Project(double t, N_Vector y, N_Vector correction, double tolerance, N_Vector error, void* self);
  static void ErrorHandler(int code, const char* module, const char* function, char* msg, void* self);

  int EvaluateRhs(double t, double* x, double* xdot);
  // The analytic Jacobian at (t, x), evaluating the outputs there first
  // unless the last right-hand side was at (t, x); returns 0 or a failure
  // flag for CVODE (recoverable, as a right-hand side's).
  int EvaluateAnalyticJacobian(double t, double* x);

  const Diagram& diagram_;
  Context& ctx_;
  const SolverOptions& options_;
  const LinearSolverChoice& choice_;
  SolverStats& stats_;
  CallbackFailures& failures_;
  sundials::Vector y_;
  sundials::Vector weights_;  // CVODE's error weights: sparse increments, projection
  std::unique_ptr<sundials::DenseSolver> dense_;
  std::unique_ptr<sundials::SparseSolver> sparse_;
  std::unique_ptr<SecondOrderSolver> second_order_;
  std::unique_ptr<sundials::KrylovSolver> krylov_;
  std::vector<double> increments_;       // sparse: per state, for each fill
  std::vector<double> analytic_values_;  // sparse and analytic: its values on the pattern
  double rhs_t_ = 0.0;                   // analytic: the last right-hand side's time and state
  std::vector<double> rhs_x_;
  std::uint64_t rhs_at_ = 0;             // and its ctx_.evaluation (0: none)
  bool linear_solver_attached_ = false;  // CVLS's counters exist only then
  bool projection_attached_ = false;     // CVODE's projection counters likewise
  std::string solver_message_;
  sundials::Cvode cvode_;  // last: freed first, before the solvers it uses
};

}  // namespace mechflow::blocks
