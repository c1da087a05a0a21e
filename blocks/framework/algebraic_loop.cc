#include "blocks/framework/algebraic_loop.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "blocks/framework/diagram.h"
#include "mech/errors.h"

namespace mechflow::blocks {

AlgebraicLoop::AlgebraicLoop(std::vector<OutputNode> inner, std::vector<OutputNode> tears,
                             const std::vector<int>& tear_offsets, const std::vector<int>& tear_widths,
                             std::vector<std::pair<int, int>> copies, std::string port, std::string hops)
    : inner_(std::move(inner)),
      tears_(std::move(tears)),
      copies_(std::move(copies)),
      port_(std::move(port)),
      description_(" through " + port_ + ":" + hops) {
  for (std::size_t i = 0; i < tear_offsets.size(); ++i)
    for (int k = 0; k < tear_widths[i]; ++k) slot_.push_back(tear_offsets[i] + k);
  const int n = num_unknowns();
  z_.setZero(n);
  g_.setZero(n);
  r_.setZero(n);
  r_old_.setZero(n);
  step_.setZero(n);
  column_.setZero(n);
  newton_matrix_.setZero(n, n);
  first_sign_.setZero(n);
  gain_jacobian_.setZero(n, n);
  lu_ = Eigen::PartialPivLU<Eigen::MatrixXd>(n);
}

void AlgebraicLoop::Evaluate(const Diagram& d, Context* ctx, const Eigen::VectorXd& z, Eigen::VectorXd* g) const {
  for (int k = 0; k < num_unknowns(); ++k) ctx->signals[slot_[k]] = z[k];
  for (const auto& [k, slot] : copies_) ctx->signals[slot] = z[k];
  // Blocks cache work per evaluation (a mechanism's solve): new tear values
  // are a new evaluation.
  ++ctx->evaluation;
  for (const OutputNode& node : inner_)
    d.block(node.block).CalcOutput(node.port, BlockContext(ctx, &d.layout(node.block)));
  for (const OutputNode& node : tears_)
    d.block(node.block).CalcOutput(node.port, BlockContext(ctx, &d.layout(node.block)));
  for (int k = 0; k < num_unknowns(); ++k) (*g)[k] = ctx->signals[slot_[k]];
  ++stats_.evaluations;
}

bool AlgebraicLoop::Converged(const Eigen::VectorXd& z, const Eigen::VectorXd& r, double* worst) const {
  bool converged = true;
  *worst = 0.0;
  for (int k = 0; k < num_unknowns(); ++k) {
    if (!std::isfinite(r[k])) return false;
    converged &= std::abs(r[k]) <= kRelativeTolerance * std::abs(z[k]) + kAbsoluteTolerance;
    *worst = std::max(*worst, std::abs(r[k]));
  }
  return converged;
}

// Forward differences about (z_, g_); the loop's signals are left at the last
// perturbed point, which the next Evaluate overwrites.
void AlgebraicLoop::UpdateJacobian(const Diagram& d, Context* ctx) const {
  const double root_eps = std::sqrt(std::numeric_limits<double>::epsilon());
  for (int k = 0; k < num_unknowns(); ++k) {
    const double scale = std::max(std::abs(z_[k]), std::abs(g_[k]));
    const double h = root_eps * (scale > 0.0 ? scale : 1.0);
    step_ = z_;
    step_[k] += h;
    Evaluate(d, ctx, step_, &column_);
    newton_matrix_.col(k) = (column_ - g_) / h;
    newton_matrix_(k, k) -= 1.0;
  }
  lu_.compute(newton_matrix_);
  have_jacobian_ = true;
  ++stats_.jacobians;
  // det(I - J) = (-1)^n det(J - I), from the factors at no cost
  const double det = (num_unknowns() % 2 ? -1.0 : 1.0) * lu_.determinant();
  if (std::isfinite(det) && (!have_gain_ || det < least_det_)) {
    least_det_ = det;
    gain_jacobian_ = newton_matrix_;
    gain_jacobian_.diagonal().array() += 1.0;
    have_gain_ = true;
  }
}

std::string AlgebraicLoop::Diagnose(double worst, bool* no_solution) const {
  std::ostringstream why;
  double gain = std::numeric_limits<double>::quiet_NaN();
  if (have_gain_) {  // the largest real eigenvalue of J: a failed solve may allocate
    const Eigen::VectorXcd eigenvalues = gain_jacobian_.eigenvalues();
    for (int k = 0; k < eigenvalues.size(); ++k)
      if (std::abs(eigenvalues[k].imag()) <= 1e-12 * std::abs(eigenvalues[k]) &&
          !(eigenvalues[k].real() <= gain))
        gain = eigenvalues[k].real();
  }
  *no_solution = !sign_changed_ && gain > 1.0;
  if (*no_solution) {
    why << "no solution: the loop returns more than it receives. Its gain (the largest eigenvalue of dG/dz, the "
        << "derivative of the loop map) reached " << gain << " > 1, and G(z) - z kept its sign over "
        << kMaxIterations << " Newton iterations (largest residual " << worst << "). A self-locking wedge or brake "
        << "does this (friction feeding its own normal force with gain mu c / b > 1): no finite force balances it; "
        << "check the friction coefficient and the lever arms";
  } else {
    why << "no convergence in " << kMaxIterations << " Newton iterations (largest residual " << worst << ")";
    if (std::isfinite(gain)) why << "; loop gain (largest eigenvalue of dG/dz) " << gain;
  }
  return why.str();
}

// Smallest over largest pivot of the LU factors: a cheap singularity test
// that, unlike Eigen's rcond(), needs no scratch memory.
double AlgebraicLoop::PivotRatio() const {
  const auto& lu = lu_.matrixLU();
  double smallest = std::numeric_limits<double>::infinity(), largest = 0.0;
  for (int k = 0; k < num_unknowns(); ++k) {
    smallest = std::min(smallest, std::abs(lu(k, k)));
    largest = std::max(largest, std::abs(lu(k, k)));
  }
  return largest > 0.0 ? smallest / largest : 0.0;
}

void AlgebraicLoop::Solve(const Diagram& d, Context* ctx) const {
  ++stats_.solves;
  for (int k = 0; k < num_unknowns(); ++k) z_[k] = ctx->signals[slot_[k]];
  if (!z_.allFinite()) z_.setZero();  // never evaluated yet
  Evaluate(d, ctx, z_, &g_);
  r_ = g_ - z_;
  sign_changed_ = false;
  have_gain_ = false;
  for (int k = 0; k < num_unknowns(); ++k) first_sign_[k] = r_[k] > 0.0 ? 1.0 : r_[k] < 0.0 ? -1.0 : 0.0;
  for (int iteration = 0;; ++iteration) {
    double worst = 0.0;
    if (Converged(z_, r_, &worst)) {
      stats_.worst_residual = std::max(stats_.worst_residual, worst);
      return;
    }
    if (!r_.allFinite()) Fail(*ctx, "a loop signal is not finite");
    if (iteration == kMaxIterations) {
      bool no_solution = false;
      const std::string why = Diagnose(worst, &no_solution);
      Fail(*ctx, why, no_solution);
    }
    if (!have_jacobian_) UpdateJacobian(d, ctx);
    const double pivot_ratio = PivotRatio();
    if (!(pivot_ratio > 1e-13)) {
      std::ostringstream why;
      why << "it has no unique solution: the loop passes its signals back with gain 1 "
          << "(I - dG/dz is singular: smallest/largest pivot " << pivot_ratio << "); largest residual " << worst;
      Fail(*ctx, why.str());
    }
    step_ = lu_.solve(r_);  // (J - I) step = r  gives  z - step
    const double before = r_.lpNorm<Eigen::Infinity>();
    z_ -= step_;
    r_old_ = r_;
    Evaluate(d, ctx, z_, &g_);
    r_ = g_ - z_;
    ++stats_.iterations;
    for (int k = 0; k < num_unknowns(); ++k) {
      if (first_sign_[k] == 0.0) first_sign_[k] = r_[k] > 0.0 ? 1.0 : r_[k] < 0.0 ? -1.0 : 0.0;
      if (r_[k] * first_sign_[k] < 0.0) sign_changed_ = true;
    }
    // A Jacobian kept from another instant may no longer fit. Broyden's
    // update makes it fit along the step just taken, for free (no extra
    // evaluations), so a slowly changing loop keeps converging in one step;
    // a step that did not even halve the residual asks for a fresh
    // difference Jacobian.
    const double after = r_.lpNorm<Eigen::Infinity>();
    if (!(after <= 0.5 * before)) {
      have_jacobian_ = false;
    } else if (after > 0.0) {
      // (J - I) += ((r_new - r_old) - (J - I) dz) dz^T / dz^T dz with dz = -step
      column_.noalias() = newton_matrix_ * step_;
      column_ += r_ - r_old_;
      newton_matrix_.noalias() -= (column_ / step_.squaredNorm()) * step_.transpose();
      lu_.compute(newton_matrix_);
    }
  }
}

void AlgebraicLoop::Fail(const Context& ctx, const std::string& why, bool no_solution) const {
  std::ostringstream msg;
  msg << "algebraic loop" << description_ << "\ncould not be solved at t = " << ctx.time << ": " << why;
  // The next attempt (a smaller step) starts from a fresh Jacobian.
  have_jacobian_ = false;
  if (no_solution) throw NoSolutionError(msg.str());
  throw SimulationError(msg.str());
}

}  // namespace mechflow::blocks
