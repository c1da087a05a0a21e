#pragma once
// The pendulum chain of problem P4 (bench/README.md) written directly,
// independently of mech/: the reference the benchmark and the tests compare
// mechflow with.
//
// Planar chain of N uniform rods (rod k: mass m_k [kg], length l_k [m], centre
// at l_k/2, rotational inertia about the centre I_k = m_k l_k^2/12) on revolute
// joints, rod 0 hinged to the ground at the origin, gravity g [m/s^2] along -y.
//
// Coordinates: ABSOLUTE angles theta_i [rad] of rod i measured from the
// horizontal (+x), counter-clockwise positive, so theta = 0 is the horizontal
// release of P4 and theta = -pi/2 hangs straight down. mechflow uses RELATIVE
// joint angles q (q_0 = theta_0, q_i = theta_i - theta_{i-1}); see
// AbsoluteToRelative and RelativeToAbsolute.
//
// Lagrangian (indices 0..N-1, S_k = sum of the masses of rods k..N-1):
//   lever of rate j in the centre velocity of rod k:
//     a_kj = l_j (j < k),  l_k/2 (j = k),  0 (j > k)
//   T = 1/2 sum_ij M_ij theta_i' theta_j',
//     M_ij = b_ij cos(theta_i - theta_j) + delta_ij I_i,
//     b_ij = sum_k m_k a_ki a_kj
//          = l_i l_j (m_k/2 + S_{k+1}),  k = max(i,j), i != j
//          = l_i^2   (m_i/4 + S_{i+1}),  i = j
//   V = g sum_i c_i sin(theta_i),  c_i = l_i (m_i/2 + S_{i+1})
// Equations of motion:
//   sum_j M_ij theta_j'' = -sum_j b_ij sin(theta_i - theta_j) theta_j'^2 - g c_i cos(theta_i)
// The mass matrix is formed in closed form (O(N^2)) and factorised by Cholesky
// (O(N^3)) at every evaluation, into storage allocated once.

#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <sundials/sundials_nvector.h>

namespace mechflow::bench {

// The chain's constants and the workspace of one evaluation.
class PendulumChain {
 public:
  // n equal rods.
  explicit PendulumChain(int n, double mass = 1.0, double length = 1.0, double g = 9.81);
  // One rod per entry; masses and lengths must have the same, non-zero size. (A
  // named function, so that {m}, {l} cannot be read as the rod count of the above.)
  static PendulumChain FromRods(const std::vector<double>& masses, const std::vector<double>& lengths,
                                double g = 9.81);

  int size() const { return n_; }
  double g() const { return g_; }

  // theta'' for absolute angles theta and rates omega (each of size()); allocates
  // nothing. False if the mass matrix failed to factorise (not for finite input).
  bool Accelerations(const Eigen::Ref<const Eigen::VectorXd>& theta, const Eigen::Ref<const Eigen::VectorXd>& omega,
                     Eigen::Ref<Eigen::VectorXd> alpha);

  // M(theta) into *m (resized).
  void MassMatrix(const Eigen::Ref<const Eigen::VectorXd>& theta, Eigen::MatrixXd* m) const;

  // Energies [J]; the potential is zero with every rod horizontal.
  double KineticEnergy(const Eigen::Ref<const Eigen::VectorXd>& theta,
                       const Eigen::Ref<const Eigen::VectorXd>& omega) const;
  double PotentialEnergy(const Eigen::Ref<const Eigen::VectorXd>& theta) const;
  double Energy(const Eigen::Ref<const Eigen::VectorXd>& theta, const Eigen::Ref<const Eigen::VectorXd>& omega) const {
    return KineticEnergy(theta, omega) + PotentialEnergy(theta);
  }
  // The energy the chain releases falling from horizontal to hanging straight
  // down, g sum_i c_i [J] (m g l N^2/2 for equal rods): the scale of energy errors.
  double EnergyScale() const;

 private:
  PendulumChain(const std::vector<double>& masses, const std::vector<double>& lengths, double g);

  int n_;
  double g_;
  Eigen::VectorXd inertia_;  // I_i = m_i l_i^2/12 (n)
  Eigen::MatrixXd b_;        // b_ij (n x n)
  Eigen::VectorXd c_;        // c_i (n)
  // workspace of Accelerations
  Eigen::VectorXd cos_, sin_, w2_;  // cos, sin of theta_i and theta_i'^2 (n)
  Eigen::MatrixXd m_;               // M(theta) (n x n)
  Eigen::LLT<Eigen::MatrixXd> llt_;
};

// Relative joint angles (q_0 = theta_0, q_i = theta_i - theta_{i-1}) from
// absolute ones, and back; the same maps convert the rates.
Eigen::VectorXd AbsoluteToRelative(const Eigen::Ref<const Eigen::VectorXd>& theta);
Eigen::VectorXd RelativeToAbsolute(const Eigen::Ref<const Eigen::VectorXd>& q);

// Options of the direct CVODE program; the defaults are those of P4.
struct DirectRunOptions {
  double rtol = 1e-6;
  double atol = 1e-8;
  double t_end = 5.0;     // [s], from t = 0
  int num_outputs = 1000;  // CVode is called at t_end k/num_outputs, k = 1..num_outputs (CV_NORMAL)
  long max_steps = 500000;
  // Installs other operations on the state vector (CVODE's clones inherit
  // them): mechflow's compiled ones, to compare with equal vector kernels.
  void (*vector_ops)(N_Vector) = nullptr;
};

// What one direct run reports.
struct DirectRunResult {
  double seconds = 0.0;    // wall time: SUNDIALS set-up, integration, teardown
  long steps = 0;
  long rhs_evals = 0;      // by the integrator
  long jac_rhs_evals = 0;  // by the difference-quotient Jacobian
  long jac_evals = 0;
  Eigen::VectorXd theta, omega;  // absolute angles [rad] and rates [rad/s] at t_end
  double energy_initial = 0.0;   // [J]
  double energy_final = 0.0;     // [J]
  double energy_drift() const { return energy_final - energy_initial; }
};

// The chain integrated directly against CVODE: state (theta, omega), BDF,
// Newton, dense direct linear solver with CVODE's difference-quotient
// Jacobian, scalar tolerances. Every SUNDIALS call is checked; a failure
// throws std::runtime_error naming the call.
DirectRunResult RunDirect(const PendulumChain& chain, const Eigen::VectorXd& theta0, const Eigen::VectorXd& omega0,
                          const DirectRunOptions& options = {});
// P4's start: every rod horizontal, at rest.
DirectRunResult RunDirect(const PendulumChain& chain, const DirectRunOptions& options = {});

}  // namespace mechflow::bench
