#include "blocks/framework/algebraic_loop.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "blocks/framework/diagram.h"
#include "mech/errors.h"

namespace mechflow::blocks {

// The run's Newton workspace for one loop, sized once.
struct AlgebraicLoop::Scratch final : BlockScratch {
  explicit Scratch(int n)
      : z(Eigen::VectorXd::Zero(n)),
        g(Eigen::VectorXd::Zero(n)),
        r(Eigen::VectorXd::Zero(n)),
        r_old(Eigen::VectorXd::Zero(n)),
        step(Eigen::VectorXd::Zero(n)),
        column(Eigen::VectorXd::Zero(n)),
        newton_matrix(Eigen::MatrixXd::Zero(n, n)),
        lu(n),
        first_sign(Eigen::VectorXd::Zero(n)),
        gain_jacobian(Eigen::MatrixXd::Zero(n, n)) {}

  Eigen::VectorXd z, g, r, r_old, step, column;
  Eigen::MatrixXd newton_matrix;  // J - I
  Eigen::PartialPivLU<Eigen::MatrixXd> lu;
  bool have_jacobian = false;
  // Over one Solve: the residual's first signs, whether one changed, and the
  // fresh Jacobian with the smallest det(I - J) (the largest gain along some
  // direction) -- kept for the diagnosis of a failure.
  Eigen::VectorXd first_sign;
  bool sign_changed = false;
  Eigen::MatrixXd gain_jacobian;
  double least_det = 0.0;
  bool have_gain = false;
  LoopStats stats;
};

AlgebraicLoop::AlgebraicLoop(int index, std::vector<OutputNode> inner, std::vector<OutputNode> tears,
                             const std::vector<int>& tear_offsets, const std::vector<int>& tear_widths,
                             std::vector<std::pair<int, int>> copies, std::string port, std::string hops)
    : index_(index),
      inner_(std::move(inner)),
      tears_(std::move(tears)),
      copies_(std::move(copies)),
      port_(std::move(port)),
      description_(" through " + port_ + ":" + hops) {
  for (std::size_t i = 0; i < tear_offsets.size(); ++i)
    for (int k = 0; k < tear_widths[i]; ++k) slot_.push_back(tear_offsets[i] + k);
}

std::unique_ptr<BlockScratch> AlgebraicLoop::MakeScratch() const { return std::make_unique<Scratch>(num_unknowns()); }

AlgebraicLoop::Scratch& AlgebraicLoop::ScratchOf(Context* ctx) const {
  const std::size_t i = static_cast<std::size_t>(index_);
  if (i >= ctx->loop_scratch.size() || !ctx->loop_scratch[i]) [[unlikely]]
    throw std::logic_error("an algebraic loop's scratch is missing: prepare the Context with InitializeStates first");
  return static_cast<Scratch&>(*ctx->loop_scratch[i]);
}

const LoopStats& AlgebraicLoop::stats(const Context& run) const {
  static const LoopStats kNone;
  const std::size_t i = static_cast<std::size_t>(index_);
  if (i >= run.loop_scratch.size() || !run.loop_scratch[i]) return kNone;
  return static_cast<const Scratch&>(*run.loop_scratch[i]).stats;
}

void AlgebraicLoop::Evaluate(const Diagram& d, Context* ctx, Scratch& s, const Eigen::VectorXd& z,
                             Eigen::VectorXd* g) const {
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
  ++s.stats.evaluations;
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

// Forward differences about (z, g); the loop's signals are left at the last
// perturbed point, which the next Evaluate overwrites.
void AlgebraicLoop::UpdateJacobian(const Diagram& d, Context* ctx, Scratch& s) const {
  const double root_eps = std::sqrt(std::numeric_limits<double>::epsilon());
  for (int k = 0; k < num_unknowns(); ++k) {
    const double scale = std::max(std::abs(s.z[k]), std::abs(s.g[k]));
    const double h = root_eps * (scale > 0.0 ? scale : 1.0);
    s.step = s.z;
    s.step[k] += h;
    Evaluate(d, ctx, s, s.step, &s.column);
    s.newton_matrix.col(k) = (s.column - s.g) / h;
    s.newton_matrix(k, k) -= 1.0;
  }
  s.lu.compute(s.newton_matrix);
  s.have_jacobian = true;
  ++s.stats.jacobians;
  // det(I - J) = (-1)^n det(J - I), from the factors at no cost
  const double det = (num_unknowns() % 2 ? -1.0 : 1.0) * s.lu.determinant();
  if (std::isfinite(det) && (!s.have_gain || det < s.least_det)) {
    s.least_det = det;
    s.gain_jacobian = s.newton_matrix;
    s.gain_jacobian.diagonal().array() += 1.0;
    s.have_gain = true;
  }
}

std::string AlgebraicLoop::Diagnose(const Scratch& s, double worst, bool* no_solution) const {
  std::ostringstream why;
  double gain = std::numeric_limits<double>::quiet_NaN();
  if (s.have_gain) {  // the largest real eigenvalue of J: a failed solve may allocate
    const Eigen::VectorXcd eigenvalues = s.gain_jacobian.eigenvalues();
    for (int k = 0; k < eigenvalues.size(); ++k)
      if (std::abs(eigenvalues[k].imag()) <= 1e-12 * std::abs(eigenvalues[k]) &&
          !(eigenvalues[k].real() <= gain))
        gain = eigenvalues[k].real();
  }
  *no_solution = !s.sign_changed && gain > 1.0;
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
double AlgebraicLoop::PivotRatio(const Scratch& s) const {
  const auto& lu = s.lu.matrixLU();
  double smallest = std::numeric_limits<double>::infinity(), largest = 0.0;
  for (int k = 0; k < num_unknowns(); ++k) {
    smallest = std::min(smallest, std::abs(lu(k, k)));
    largest = std::max(largest, std::abs(lu(k, k)));
  }
  return largest > 0.0 ? smallest / largest : 0.0;
}

void AlgebraicLoop::Solve(const Diagram& d, Context* ctx) const {
  Scratch& s = ScratchOf(ctx);
  ++s.stats.solves;
  for (int k = 0; k < num_unknowns(); ++k) s.z[k] = ctx->signals[slot_[k]];
  if (!s.z.allFinite()) s.z.setZero();  // never evaluated yet
  Evaluate(d, ctx, s, s.z, &s.g);
  s.r = s.g - s.z;
  s.sign_changed = false;
  s.have_gain = false;
  for (int k = 0; k < num_unknowns(); ++k) s.first_sign[k] = s.r[k] > 0.0 ? 1.0 : s.r[k] < 0.0 ? -1.0 : 0.0;
  for (int iteration = 0;; ++iteration) {
    double worst = 0.0;
    if (Converged(s.z, s.r, &worst)) {
      s.stats.worst_residual = std::max(s.stats.worst_residual, worst);
      return;
    }
    if (!s.r.allFinite()) Fail(*ctx, s, "a loop signal is not finite");
    if (iteration == kMaxIterations) {
      bool no_solution = false;
      const std::string why = Diagnose(s, worst, &no_solution);
      Fail(*ctx, s, why, no_solution);
    }
    if (!s.have_jacobian) UpdateJacobian(d, ctx, s);
    const double pivot_ratio = PivotRatio(s);
    if (!(pivot_ratio > 1e-13)) {
      std::ostringstream why;
      why << "it has no unique solution: the loop passes its signals back with gain 1 "
          << "(I - dG/dz is singular: smallest/largest pivot " << pivot_ratio << "); largest residual " << worst;
      Fail(*ctx, s, why.str());
    }
    s.step = s.lu.solve(s.r);  // (J - I) step = r  gives  z - step
    const double before = s.r.lpNorm<Eigen::Infinity>();
    s.z -= s.step;
    s.r_old = s.r;
    Evaluate(d, ctx, s, s.z, &s.g);
    s.r = s.g - s.z;
    ++s.stats.iterations;
    for (int k = 0; k < num_unknowns(); ++k) {
      if (s.first_sign[k] == 0.0) s.first_sign[k] = s.r[k] > 0.0 ? 1.0 : s.r[k] < 0.0 ? -1.0 : 0.0;
      if (s.r[k] * s.first_sign[k] < 0.0) s.sign_changed = true;
    }
    // A Jacobian kept from another instant may no longer fit. Broyden's
    // update makes it fit along the step just taken, for free (no extra
    // evaluations), so a slowly changing loop keeps converging in one step;
    // a step that did not even halve the residual asks for a fresh
    // difference Jacobian.
    const double after = s.r.lpNorm<Eigen::Infinity>();
    if (!(after <= 0.5 * before)) {
      s.have_jacobian = false;
    } else if (after > 0.0) {
      // (J - I) += ((r_new - r_old) - (J - I) dz) dz^T / dz^T dz with dz = -step
      s.column.noalias() = s.newton_matrix * s.step;
      s.column += s.r - s.r_old;
      s.newton_matrix.noalias() -= (s.column / s.step.squaredNorm()) * s.step.transpose();
      s.lu.compute(s.newton_matrix);
    }
  }
}

void AlgebraicLoop::Fail(const Context& ctx, Scratch& s, const std::string& why, bool no_solution) const {
  std::ostringstream msg;
  msg << "algebraic loop" << description_ << "\ncould not be solved at t = " << ctx.time << ": " << why;
  // The next attempt (a smaller step) starts from a fresh Jacobian.
  s.have_jacobian = false;
  if (no_solution) throw NoSolutionError(msg.str());
  throw SimulationError(msg.str());
}

}  // namespace mechflow::blocks
