#pragma once
// Solving with the loop constraints (mech/constraints.h): constrained
// accelerations and multipliers, projections of positions and velocities
// onto the constraints, and assembly.
//
// Rows of J that are exactly zero (a planar loop's out-of-plane ones) are
// left out of the solves. The constraint Jacobian J may be rank deficient for good (a planar loop's
// out-of-plane rows, Bricard's linkage, Convel1) or for a moment (a
// parallelogram passing its collinear position, where it has one more
// degree of freedom). Every solve therefore factors a Gram matrix of the
// full J afresh -- G = J J^T for projections, G = J M^-1 J^T for
// accelerations -- by Cholesky with symmetric pivoting (Eigen's LDLT), and
// inverts each pivot d as d / (d^2 + mu^2), mu = kDamping * (largest pivot):
//   - well-conditioned directions are solved exactly (to (mu/d)^2);
//   - redundant directions (pivots at round-off) contribute nothing;
//   - a direction that goes singular fades out smoothly instead of blowing
//     up (damped least squares), so the right-hand side stays continuous.
// The damping is kept tiny on purpose. Near a dead centre the equations
// are ill-conditioned: a velocity error along the opened direction makes
// constraint forces that grow like 1/sigma, so a step landing very close to
// the singular position can fail at tight tolerances (the failure names the
// joint, SingularPositionNote). Damping those directions more, relative to
// the weakest one at the start, let such runs pass -- by releasing the
// constraint there: across 70 runs of coupled parallelograms the energy,
// which must stay constant, then changed by up to 1600% in runs that
// finished. A clear failure is better than that; undamped, none of the 70
// gave a wrong answer, 48 finished, 22 failed with the position named.
// The run-time projections are another matter (ProjectPositions'
// velocity_tolerance): near a dead centre they cannot fix the weak direction
// within a tight tolerance, and enforcing it there anyway is what stopped
// those runs; they damp it by the tolerance and the accelerations keep it.
// Why not select the independent rows once, at the start: a row set that is
// independent there can become dependent later while J keeps its rank. In
// Bricard's linkage at t = 0.894 s the rows chosen at t = 0 had a least
// singular value of 5e-5 while J's five stayed above 1.1; the round-off
// they amplified froze the integrator's time at rtol 1e-11.

#include <span>
#include <string>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "mech/constraints.h"

namespace mechflow::mech {

// Per-run storage for the solves: sized once, no allocation afterwards.
struct ConstraintWorkspace {
  ConstraintWorkspace(const Model& model, const Constraints& constraints);

  Eigen::MatrixXd M, J;
  std::vector<int> rows;   // the rows of J that are not exactly zero
  Eigen::MatrixXd Jc;      // those rows (mc x nv)
  Eigen::MatrixXd X;       // L^-1 Jc^T with M~ = L L^T = M + alpha J^T J (nv x mc)
  Eigen::MatrixXd G;       // the Gram matrix of the last solve (mc x mc, lower half)
  Eigen::LLT<Eigen::MatrixXd> M_llt;
  Eigen::LDLT<Eigen::MatrixXd> G_ldlt;
  Eigen::VectorXd phi, psi, bias, lambda, step, rhs, pivoted, vfree;
  std::vector<Vec6> scratch;
  std::vector<Vec6> loads;  // segment loads with the constraint wrenches added
  std::vector<double> h;    // inverse dynamics with v' = 0
  std::vector<double> zero;

  // The numerical rank of G at the last solve, the rank found at assembly
  // (the loops' generic rank), and the constraint row whose pivot was the
  // weakest of the generic-rank ones (what turns singular first).
  int rank = 0;
  int generic_rank = -1;
  int weakest_row = -1;
  // the weakest generic pivot of J J^T at assembly and at the last projection
  double reference_pivot = 0.0, weakest_pivot = 0.0;
  std::vector<int> order;  // pivot order of the last factorisation (into rows)
};

// Constrained accelerations: M v' = f + J^T lambda with J v' + bias = 0,
// where f = tau - h. Reads ws->M (overwritten), J, bias (filled by the
// caller) and f; writes vdot (nv) and ws->lambda (the wrench body 2
// receives, per row).
void SolveConstrainedAccelerations(std::span<const double> f, std::span<double> vdot, ConstraintWorkspace* ws);

// Moves q (and then v) onto the constraint manifold by Gauss-Newton with
// least-norm steps; returns the final position residual norm. Quaternion
// coordinates are updated through their rotation vector.
// `velocity_tolerance` > 0 (the integrator's, for v) makes the projections
// tolerance-aware near a singular position: directions so weak that the
// round-off of the residuals would move v by more than it (at a dead centre,
// eps L |J| |v| / sigma^2) are damped rather than enforced; 0 enforces
// every direction down to round-off (assembly).
double ProjectPositions(const Model& model, const Constraints& constraints, double t, std::span<double> q,
                        std::span<const double> v, double tolerance, int max_iterations, Kinematics* kin,
                        ConstraintWorkspace* ws, double velocity_tolerance = 0.0);
// Assembly, first phase: closes the loops by moving only the coordinates of
// the loop-closing joints themselves (their ghost segments), so consistent
// user coordinates are kept exactly. Returns the residual norm reached.
double AssembleCutCoordinates(const Model& model, const Constraints& constraints, std::span<double> q,
                              std::span<const double> v, Kinematics* kin, ConstraintWorkspace* ws);

// Assembly of velocities, first phase: the loop-closing joints' own rates
// take up what they can, so consistent user velocities are kept exactly.
void AssembleCutVelocities(const Model& model, const Constraints& constraints, std::span<const double> q,
                           std::span<double> v, Kinematics* kin, ConstraintWorkspace* ws);

void ProjectVelocities(const Model& model, const Constraints& constraints, double t, std::span<const double> q,
                       std::span<double> v, Kinematics* kin, ConstraintWorkspace* ws,
                       double velocity_tolerance = 0.0);

// Records the rank of the loops at the current (assembled) position as their
// generic rank; later solves compare against it.
void RecordGenericRank(const Model& model, const Constraints& constraints, const Kinematics& kin,
                       ConstraintWorkspace* ws);

// When the last solves found the loops below their generic rank, or their
// weakest direction below a fifth of its strength at the start: a sentence
// naming the joint whose constraint became (nearly) dependent; empty
// otherwise.
std::string SingularPositionNote(const Model& model, const Constraints& constraints,
                                 const ConstraintWorkspace& ws);

}  // namespace mechflow::mech
