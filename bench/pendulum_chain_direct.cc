#include "bench/pendulum_chain_direct.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "bench/direct_cvode.h"

namespace mechflow::bench {
namespace {

std::vector<double> Repeat(int n, double value) {
  if (n < 1) throw std::invalid_argument("PendulumChain: needs at least one rod, got " + std::to_string(n));
  return std::vector<double>(static_cast<std::size_t>(n), value);
}

}  // namespace

PendulumChain::PendulumChain(int n, double mass, double length, double g)
    : PendulumChain(Repeat(n, mass), Repeat(n, length), g) {}

PendulumChain PendulumChain::FromRods(const std::vector<double>& masses, const std::vector<double>& lengths,
                                      double g) {
  return PendulumChain(masses, lengths, g);
}

PendulumChain::PendulumChain(const std::vector<double>& masses, const std::vector<double>& lengths, double g)
    : n_(static_cast<int>(masses.size())), g_(g) {
  if (masses.empty() || masses.size() != lengths.size())
    throw std::invalid_argument("PendulumChain: " + std::to_string(masses.size()) + " masses and " +
                                std::to_string(lengths.size()) + " lengths; need the same non-zero number");
  for (int i = 0; i < n_; ++i)
    if (!(masses[i] > 0.0) || !(lengths[i] > 0.0))
      throw std::invalid_argument("PendulumChain: rod " + std::to_string(i) + " needs a positive mass and length");

  // suffix sums of the masses: after[k] = S_{k+1}, the mass beyond rod k
  std::vector<double> after(n_, 0.0);
  for (int k = n_ - 2; k >= 0; --k) after[k] = after[k + 1] + masses[k + 1];

  inertia_.resize(n_);
  c_.resize(n_);
  b_.resize(n_, n_);
  for (int i = 0; i < n_; ++i) {
    const double li = lengths[i];
    inertia_(i) = masses[i] * li * li / 12.0;
    c_(i) = li * (masses[i] / 2.0 + after[i]);
    for (int j = 0; j < n_; ++j) {
      const int k = std::max(i, j);
      b_(i, j) = lengths[i] * lengths[j] * (masses[k] * (i == j ? 0.25 : 0.5) + after[k]);
    }
  }

  cos_.resize(n_);
  sin_.resize(n_);
  w2_.resize(n_);
  m_.resize(n_, n_);
  llt_.compute(Eigen::MatrixXd::Identity(n_, n_));  // sized now; an empty LLT leaves its status uninitialised
}

bool PendulumChain::Accelerations(const Eigen::Ref<const Eigen::VectorXd>& theta,
                                  const Eigen::Ref<const Eigen::VectorXd>& omega, Eigen::Ref<Eigen::VectorXd> alpha) {
  // one sine and cosine per rod; those of the differences follow from them
  for (int i = 0; i < n_; ++i) {
    cos_(i) = std::cos(theta(i));
    sin_(i) = std::sin(theta(i));
    w2_(i) = omega(i) * omega(i);
  }
  // mass matrix (lower triangle, all Cholesky reads) and right-hand side
  for (int i = 0; i < n_; ++i) {
    double r = -g_ * c_(i) * cos_(i);
    for (int j = 0; j < n_; ++j) {
      const double sin_ij = sin_(i) * cos_(j) - cos_(i) * sin_(j);  // sin(theta_i - theta_j)
      r -= b_(i, j) * sin_ij * w2_(j);
      if (j <= i) m_(i, j) = b_(i, j) * (cos_(i) * cos_(j) + sin_(i) * sin_(j));
    }
    m_(i, i) += inertia_(i);
    alpha(i) = r;
  }
  // solve M alpha = r
  llt_.compute(m_);
  if (llt_.info() != Eigen::Success) return false;
  llt_.solveInPlace(alpha);
  return true;
}

void PendulumChain::MassMatrix(const Eigen::Ref<const Eigen::VectorXd>& theta, Eigen::MatrixXd* m) const {
  m->resize(n_, n_);
  for (int i = 0; i < n_; ++i)
    for (int j = 0; j < n_; ++j) (*m)(i, j) = b_(i, j) * std::cos(theta(i) - theta(j)) + (i == j ? inertia_(i) : 0.0);
}

double PendulumChain::KineticEnergy(const Eigen::Ref<const Eigen::VectorXd>& theta,
                                    const Eigen::Ref<const Eigen::VectorXd>& omega) const {
  double t = 0.0;
  for (int i = 0; i < n_; ++i) {
    t += inertia_(i) * omega(i) * omega(i);
    for (int j = 0; j < n_; ++j) t += b_(i, j) * std::cos(theta(i) - theta(j)) * omega(i) * omega(j);
  }
  return 0.5 * t;
}

double PendulumChain::PotentialEnergy(const Eigen::Ref<const Eigen::VectorXd>& theta) const {
  double v = 0.0;
  for (int i = 0; i < n_; ++i) v += c_(i) * std::sin(theta(i));
  return g_ * v;
}

double PendulumChain::EnergyScale() const { return g_ * c_.sum(); }

Eigen::VectorXd AbsoluteToRelative(const Eigen::Ref<const Eigen::VectorXd>& theta) {
  Eigen::VectorXd q(theta.size());
  for (Eigen::Index i = 0; i < theta.size(); ++i) q(i) = i == 0 ? theta(0) : theta(i) - theta(i - 1);
  return q;
}

Eigen::VectorXd RelativeToAbsolute(const Eigen::Ref<const Eigen::VectorXd>& q) {
  Eigen::VectorXd theta(q.size());
  double sum = 0.0;
  for (Eigen::Index i = 0; i < q.size(); ++i) theta(i) = sum += q(i);
  return theta;
}

namespace {

using Clock = std::chrono::steady_clock;

// y = (theta, omega), y' = (omega, theta'')
int ChainRhs(double, N_Vector y, N_Vector ydot, void* user) {
  auto& chain = *static_cast<PendulumChain*>(user);
  const int n = chain.size();
  const double* s = N_VGetArrayPointer(y);
  double* ds = N_VGetArrayPointer(ydot);
  const Eigen::Map<const Eigen::VectorXd> theta(s, n), omega(s + n, n);
  Eigen::Map<Eigen::VectorXd> theta_rate(ds, n), omega_rate(ds + n, n);
  theta_rate = omega;
  return chain.Accelerations(theta, omega, omega_rate) ? 0 : -1;
}

using direct::Check;
using direct::CheckPointer;
using direct::Solver;

}  // namespace

DirectRunResult RunDirect(const PendulumChain& chain, const Eigen::VectorXd& theta0, const Eigen::VectorXd& omega0,
                          const DirectRunOptions& options) {
  const int n = chain.size();
  if (theta0.size() != n || omega0.size() != n)
    throw std::invalid_argument("RunDirect: initial state of size " + std::to_string(theta0.size()) + " + " +
                                std::to_string(omega0.size()) + " for a chain of " + std::to_string(n) + " rods");
  if (options.num_outputs < 1 || !(options.t_end > 0.0))
    throw std::invalid_argument("RunDirect: needs t_end > 0 and at least one output time");
  DirectRunResult result;

  const auto start = Clock::now();
  {
    PendulumChain work = chain;  // the right-hand side's own workspace
    Solver s;
    Check(SUNContext_Create(nullptr, &s.ctx), "SUNContext_Create");
    s.y = CheckPointer(N_VNew_Serial(2 * n, s.ctx), "N_VNew_Serial");
    if (options.vector_ops) options.vector_ops(s.y);
    double* y = N_VGetArrayPointer(s.y);
    Eigen::Map<Eigen::VectorXd>(y, n) = theta0;
    Eigen::Map<Eigen::VectorXd>(y + n, n) = omega0;
    s.a = CheckPointer(SUNDenseMatrix(2 * n, 2 * n, s.ctx), "SUNDenseMatrix");
    s.ls = CheckPointer(SUNLinSol_Dense(s.y, s.a, s.ctx), "SUNLinSol_Dense");
    s.cvode = CheckPointer(CVodeCreate(CV_BDF, s.ctx), "CVodeCreate");
    Check(CVodeInit(s.cvode, ChainRhs, 0.0, s.y), "CVodeInit");
    Check(CVodeSetUserData(s.cvode, &work), "CVodeSetUserData");
    Check(CVodeSStolerances(s.cvode, options.rtol, options.atol), "CVodeSStolerances");
    Check(CVodeSetLinearSolver(s.cvode, s.ls, s.a), "CVodeSetLinearSolver");
    Check(CVodeSetMaxNumSteps(s.cvode, options.max_steps), "CVodeSetMaxNumSteps");
    Check(CVodeSetStopTime(s.cvode, options.t_end), "CVodeSetStopTime");  // never step past the end

    double t = 0.0;
    for (int k = 1; k <= options.num_outputs; ++k) {
      const double t_out = k == options.num_outputs ? options.t_end : options.t_end * k / options.num_outputs;
      Check(CVode(s.cvode, t_out, s.y, &t, CV_NORMAL), "CVode");
    }

    Check(CVodeGetNumSteps(s.cvode, &result.steps), "CVodeGetNumSteps");
    Check(CVodeGetNumRhsEvals(s.cvode, &result.rhs_evals), "CVodeGetNumRhsEvals");
    Check(CVodeGetNumLinRhsEvals(s.cvode, &result.jac_rhs_evals), "CVodeGetNumLinRhsEvals");
    Check(CVodeGetNumJacEvals(s.cvode, &result.jac_evals), "CVodeGetNumJacEvals");
    result.theta = Eigen::Map<const Eigen::VectorXd>(y, n);
    result.omega = Eigen::Map<const Eigen::VectorXd>(y + n, n);
  }
  result.seconds = std::chrono::duration<double>(Clock::now() - start).count();

  result.energy_initial = chain.Energy(theta0, omega0);
  result.energy_final = chain.Energy(result.theta, result.omega);
  return result;
}

DirectRunResult RunDirect(const PendulumChain& chain, const DirectRunOptions& options) {
  return RunDirect(chain, Eigen::VectorXd::Zero(chain.size()), Eigen::VectorXd::Zero(chain.size()), options);
}

}  // namespace mechflow::bench
