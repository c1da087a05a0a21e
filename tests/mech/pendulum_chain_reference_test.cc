// The P4 reference (bench/pendulum_chain_direct.h) checked on its own, by code
// paths that share nothing with it: one rod against the compound pendulum, two
// rods against the double pendulum's hand-derived equations, any number of
// rods against the Lagrange equations of the rods' centre positions, and the
// direct CVODE program against conservation of energy.
//
// Eigen allocates through malloc, so the allocation test counts malloc itself
// (tests/malloc_counter.h): this executable's malloc family
// replaces the C library's for the whole process.

#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "bench/pendulum_chain_direct.h"
#include "tests/malloc_counter.h"

namespace mechflow::bench {
namespace {

using Eigen::VectorXd;

constexpr double kPi = 3.14159265358979323846;
constexpr double kG = 9.81;

VectorXd Accelerations(PendulumChain& chain, const VectorXd& theta, const VectorXd& omega) {
  VectorXd alpha(chain.size());
  EXPECT_TRUE(chain.Accelerations(theta, omega, alpha));
  return alpha;
}

// ---------------------------------------------------------------------------
// one rod: the compound pendulum, I_O theta'' = -m g (l/2) cos(theta), I_O = m l^2/3

TEST(PendulumChainReferenceTest, OneRodIsTheCompoundPendulum) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> angle(-kPi, kPi), rate(-6.0, 6.0), size(0.2, 3.0);
  for (int trial = 0; trial < 50; ++trial) {
    const double m = size(rng), l = size(rng), th = angle(rng), w = rate(rng);
    PendulumChain chain = PendulumChain::FromRods({m}, {l}, kG);
    const double io = m * l * l / 3.0;
    const VectorXd theta = VectorXd::Constant(1, th), omega = VectorXd::Constant(1, w);
    EXPECT_NEAR(Accelerations(chain, theta, omega)(0), -m * kG * l / 2.0 * std::cos(th) / io, 1e-12 * kG / l);
    EXPECT_NEAR(chain.Energy(theta, omega), 0.5 * io * w * w + m * kG * l / 2.0 * std::sin(th),
                1e-12 * m * (kG * l + l * l * w * w));
  }
}

// Small swings about hanging straight down have the period 2 pi sqrt(I_O / (m g l/2)).
// After K periods of the closed form the swing's phase error is -2 pi K delta, delta
// the relative error of the period (amplitude eps adds eps^2/16 to it).
TEST(PendulumChainReferenceTest, OneRodSwingsWithTheCompoundPendulumPeriod) {
  const double eps = 1e-3;
  const int periods = 10;
  for (const auto& [m, l] : std::vector<std::pair<double, double>>{{1.0, 1.0}, {2.5, 0.4}}) {
    SCOPED_TRACE("m = " + std::to_string(m) + " kg, l = " + std::to_string(l) + " m");
    const PendulumChain chain = PendulumChain::FromRods({m}, {l}, kG);
    const double period = 2.0 * kPi * std::sqrt((m * l * l / 3.0) / (m * kG * l / 2.0));
    DirectRunOptions options;
    options.rtol = 1e-11;
    options.atol = 1e-13;
    options.t_end = periods * period;
    options.num_outputs = 1;
    const VectorXd theta0 = VectorXd::Constant(1, -kPi / 2.0 + eps);
    const DirectRunResult run = RunDirect(chain, theta0, VectorXd::Zero(1), options);

    const double x = run.theta(0) + kPi / 2.0, y = -run.omega(0) * period / (2.0 * kPi);
    const double delta = -std::atan2(y, x) / (2.0 * kPi * periods);
    EXPECT_NEAR(std::hypot(x, y), eps, 1e-5 * eps);
    EXPECT_NEAR(delta, eps * eps / 16.0, 2e-9);  // measured 6.226e-8 at m = l = 1
  }
}

// ---------------------------------------------------------------------------
// two rods: the double pendulum of uniform rods, Lagrangian derived by hand
//   T = 1/2 (m1 l1^2/3 + m2 l1^2) w1^2 + 1/2 (m2 l2^2/3) w2^2 + 1/2 m2 l1 l2 cos(t1 - t2) w1 w2
//   V = g ((m1/2 + m2) l1 sin t1 + m2 l2/2 sin t2)
//   (m1/3 + m2) l1^2 a1 + m2 l1 l2/2 cos(t1 - t2) a2
//       = -m2 l1 l2/2 sin(t1 - t2) w2^2 - g (m1/2 + m2) l1 cos t1
//   m2 l1 l2/2 cos(t1 - t2) a1 + m2 l2^2/3 a2
//       =  m2 l1 l2/2 sin(t1 - t2) w1^2 - g m2 l2/2 cos t2

struct DoublePendulum {
  double m1, m2, l1, l2;

  void Accelerations(double t1, double t2, double w1, double w2, double* a1, double* a2) const {
    const double d = t1 - t2, k = m2 * l1 * l2 / 2.0;
    const double p = (m1 / 3.0 + m2) * l1 * l1, q = k * std::cos(d), r = m2 * l2 * l2 / 3.0;
    const double f1 = -k * std::sin(d) * w2 * w2 - kG * (m1 / 2.0 + m2) * l1 * std::cos(t1);
    const double f2 = k * std::sin(d) * w1 * w1 - kG * m2 * l2 / 2.0 * std::cos(t2);
    const double det = p * r - q * q;
    *a1 = (f1 * r - q * f2) / det;
    *a2 = (p * f2 - q * f1) / det;
  }
  double Kinetic(double t1, double t2, double w1, double w2) const {
    return 0.5 * (m1 / 3.0 + m2) * l1 * l1 * w1 * w1 + 0.5 * m2 * l2 * l2 / 3.0 * w2 * w2 +
           0.5 * m2 * l1 * l2 * std::cos(t1 - t2) * w1 * w2;
  }
  double Potential(double t1, double t2) const {
    return kG * ((m1 / 2.0 + m2) * l1 * std::sin(t1) + m2 * l2 / 2.0 * std::sin(t2));
  }
};

TEST(PendulumChainReferenceTest, TwoRodsFollowTheDoublePendulumEquations) {
  std::mt19937 rng(22);
  std::uniform_real_distribution<double> angle(-kPi, kPi), rate(-8.0, 8.0), size(0.3, 2.0);
  for (int trial = 0; trial < 200; ++trial) {
    const DoublePendulum dp{size(rng), size(rng), size(rng), size(rng)};
    PendulumChain chain = PendulumChain::FromRods({dp.m1, dp.m2}, {dp.l1, dp.l2}, kG);
    const double t1 = angle(rng), t2 = angle(rng), w1 = rate(rng), w2 = rate(rng);
    const VectorXd theta = (VectorXd(2) << t1, t2).finished(), omega = (VectorXd(2) << w1, w2).finished();
    double a1, a2;
    dp.Accelerations(t1, t2, w1, w2, &a1, &a2);
    const VectorXd alpha = Accelerations(chain, theta, omega);
    const double scale = 1.0 + std::abs(a1) + std::abs(a2);
    EXPECT_NEAR(alpha(0), a1, 1e-12 * scale) << "trial " << trial;
    EXPECT_NEAR(alpha(1), a2, 1e-12 * scale) << "trial " << trial;
    const double kinetic = dp.Kinetic(t1, t2, w1, w2), potential = dp.Potential(t1, t2);
    EXPECT_NEAR(chain.KineticEnergy(theta, omega), kinetic, 1e-12 * (1.0 + std::abs(kinetic)));
    EXPECT_NEAR(chain.PotentialEnergy(theta), potential, 1e-12 * (1.0 + std::abs(potential)));
  }
}

// ---------------------------------------------------------------------------
// any number of rods: the Lagrange equations of the rods themselves. The test
// builds each rod's centre position and velocity from the geometry, forms the
// momenta p = dT/dw and the forces dL/dtheta (central differences), and asks
// d/dt p - dL/dtheta = dp/dtheta w + dp/dw alpha - dL/dtheta = 0 for the
// reference's alpha.

struct Rods {
  std::vector<double> m, l;
  int n() const { return static_cast<int>(m.size()); }

  // velocity of rod k's centre: sum over joints j < k of l_j w_j e'(t_j), plus l_k/2 w_k e'(t_k)
  void CentreVelocity(int k, const VectorXd& t, const VectorXd& w, double* vx, double* vy) const {
    *vx = *vy = 0.0;
    for (int j = 0; j <= k; ++j) {
      const double arm = j < k ? l[j] : l[k] / 2.0;
      *vx -= arm * w(j) * std::sin(t(j));
      *vy += arm * w(j) * std::cos(t(j));
    }
  }
  double Lagrangian(const VectorXd& t, const VectorXd& w) const {
    double kinetic = 0.0, potential = 0.0, y_joint = 0.0;
    for (int k = 0; k < n(); ++k) {
      double vx, vy;
      CentreVelocity(k, t, w, &vx, &vy);
      kinetic += 0.5 * m[k] * (vx * vx + vy * vy) + 0.5 * (m[k] * l[k] * l[k] / 12.0) * w(k) * w(k);
      potential += m[k] * kG * (y_joint + l[k] / 2.0 * std::sin(t(k)));
      y_joint += l[k] * std::sin(t(k));
    }
    return kinetic - potential;
  }
  // p_i = dT/dw_i = sum_k m_k v_k . dv_k/dw_i + I_i w_i (exact: v_k is linear in w)
  VectorXd Momenta(const VectorXd& t, const VectorXd& w) const {
    VectorXd p = VectorXd::Zero(n());
    for (int k = 0; k < n(); ++k) {
      double vx, vy;
      CentreVelocity(k, t, w, &vx, &vy);
      for (int i = 0; i <= k; ++i) {
        const double arm = i < k ? l[i] : l[k] / 2.0;
        p(i) += m[k] * arm * (-vx * std::sin(t(i)) + vy * std::cos(t(i)));
      }
      p(k) += m[k] * l[k] * l[k] / 12.0 * w(k);
    }
    return p;
  }
};

TEST(PendulumChainReferenceTest, AnyNumberOfRodsSatisfiesTheLagrangeEquations) {
  std::mt19937 rng(33);
  std::uniform_real_distribution<double> angle(-kPi, kPi), rate(-4.0, 4.0), size(0.3, 2.0);
  for (const int n : {3, 5, 8}) {
    for (int trial = 0; trial < 20; ++trial) {
      Rods rods;
      for (int k = 0; k < n; ++k) rods.m.push_back(size(rng)), rods.l.push_back(size(rng));
      PendulumChain chain = PendulumChain::FromRods(rods.m, rods.l, kG);
      VectorXd t(n), w(n);
      for (int k = 0; k < n; ++k) t(k) = angle(rng), w(k) = rate(rng);
      const VectorXd alpha = Accelerations(chain, t, w);

      const double h = 1e-5;
      const VectorXd dp_dt_w = (rods.Momenta(t + h * w, w) - rods.Momenta(t - h * w, w)) / (2.0 * h);
      VectorXd dp_dw_alpha = (rods.Momenta(t, w + alpha) - rods.Momenta(t, w - alpha)) / 2.0;  // linear in w
      VectorXd force(n);
      for (int i = 0; i < n; ++i) {
        const VectorXd e = VectorXd::Unit(n, i) * h;
        force(i) = (rods.Lagrangian(t + e, w) - rods.Lagrangian(t - e, w)) / (2.0 * h);
      }
      const VectorXd residual = dp_dt_w + dp_dw_alpha - force;
      EXPECT_LT(residual.cwiseAbs().maxCoeff(), 1e-6 * (1.0 + force.cwiseAbs().maxCoeff()))
          << "n = " << n << ", trial " << trial << ", residual " << residual.transpose();

      // and the mass matrix is dp/dw
      Eigen::MatrixXd mass;
      chain.MassMatrix(t, &mass);
      for (int j = 0; j < n; ++j) {
        const VectorXd column = rods.Momenta(t, VectorXd::Unit(n, j));
        EXPECT_LT((mass.col(j) - column).cwiseAbs().maxCoeff(), 1e-12 * (1.0 + column.cwiseAbs().maxCoeff()));
      }
    }
  }
}

TEST(PendulumChainReferenceTest, EqualRodsReleaseMglNSquaredOverTwo) {
  for (const int n : {1, 2, 10, 50}) {
    const PendulumChain chain(n);
    EXPECT_NEAR(chain.EnergyScale(), 1.0 * kG * 1.0 * n * n / 2.0, 1e-12 * n * n);
    const VectorXd hanging = VectorXd::Constant(n, -kPi / 2.0);
    EXPECT_NEAR(chain.PotentialEnergy(hanging), -chain.EnergyScale(), 1e-12 * n * n);
  }
}

// ---------------------------------------------------------------------------
// coordinates

TEST(PendulumChainReferenceTest, RelativeAndAbsoluteAnglesConvertBothWays) {
  const VectorXd theta = (VectorXd(4) << 0.5, 1.5, -0.25, 0.0).finished();
  const VectorXd q = AbsoluteToRelative(theta);
  EXPECT_EQ(q, (VectorXd(4) << 0.5, 1.0, -1.75, 0.25).finished());
  EXPECT_EQ(RelativeToAbsolute(q), theta);

  std::mt19937 rng(44);
  std::uniform_real_distribution<double> angle(-kPi, kPi);
  VectorXd random(30);
  for (auto& x : random) x = angle(rng);
  EXPECT_LT((RelativeToAbsolute(AbsoluteToRelative(random)) - random).cwiseAbs().maxCoeff(), 1e-13);
  EXPECT_LT((AbsoluteToRelative(RelativeToAbsolute(random)) - random).cwiseAbs().maxCoeff(), 1e-13);
}

// ---------------------------------------------------------------------------
// the direct CVODE program

TEST(PendulumChainReferenceTest, DirectRunConservesEnergyAtTightTolerances) {
  for (const int n : {2, 10}) {
    const PendulumChain chain(n);
    DirectRunOptions options;
    options.rtol = 1e-10;
    options.atol = 1e-12;
    const DirectRunResult run = RunDirect(chain, options);
    EXPECT_EQ(run.energy_initial, 0.0);
    EXPECT_LT(std::abs(run.energy_drift()) / chain.EnergyScale(), 1e-7)
        << "n = " << n << ": drift " << run.energy_drift() << " J of " << chain.EnergyScale() << " J";
    EXPECT_NEAR(run.energy_final, chain.Energy(run.theta, run.omega), 0.0);
  }
}

TEST(PendulumChainReferenceTest, DirectRunAtTheP4SettingsReportsItsWork) {
  const DirectRunOptions defaults;
  EXPECT_EQ(defaults.rtol, 1e-6);
  EXPECT_EQ(defaults.atol, 1e-8);
  EXPECT_EQ(defaults.t_end, 5.0);

  const PendulumChain chain(2);
  const DirectRunResult run = RunDirect(chain);
  EXPECT_GT(run.steps, 100);
  EXPECT_GE(run.rhs_evals, run.steps);
  EXPECT_GT(run.jac_evals, 0);
  EXPECT_EQ(run.jac_rhs_evals, 2 * 2 * run.jac_evals);  // one per state per difference-quotient Jacobian
  EXPECT_GT(run.seconds, 0.0);
  ASSERT_EQ(run.theta.size(), 2);
  ASSERT_EQ(run.omega.size(), 2);
  EXPECT_TRUE(run.theta.allFinite() && run.omega.allFinite());
  EXPECT_LT(std::abs(run.energy_drift()) / chain.EnergyScale(), 1e-3);
  // the chain has fallen: it holds less potential energy than at the start
  EXPECT_LT(chain.PotentialEnergy(run.theta), -0.01 * chain.EnergyScale());
}

TEST(PendulumChainReferenceTest, DirectRunRejectsAMismatchedState) {
  const PendulumChain chain(3);
  EXPECT_THROW(RunDirect(chain, VectorXd::Zero(2), VectorXd::Zero(3)), std::invalid_argument);
  EXPECT_THROW(PendulumChain(0), std::invalid_argument);
  EXPECT_THROW(PendulumChain::FromRods({1.0, 1.0}, {1.0}), std::invalid_argument);
  EXPECT_THROW(PendulumChain::FromRods({1.0, -1.0}, {1.0, 1.0}), std::invalid_argument);
}

TEST(PendulumChainReferenceTest, AccelerationsAllocateNothing) {
  if (!kMallocCounted) GTEST_SKIP() << "allocation counting needs the C library's malloc (not AddressSanitizer's)";
  for (const int n : {1, 10, 50}) {
    PendulumChain chain(n);
    const VectorXd theta = VectorXd::LinSpaced(n, -1.0, 2.0), omega = VectorXd::LinSpaced(n, 3.0, -1.0);
    VectorXd alpha(n);
    ASSERT_TRUE(chain.Accelerations(theta, omega, alpha));  // warm
    g_calls = 0;
    g_counting = true;
    bool ok = true;
    for (int k = 0; k < 10; ++k) ok = ok && chain.Accelerations(theta, omega, alpha);
    g_counting = false;
    EXPECT_TRUE(ok);
    EXPECT_EQ(g_calls.load(), 0) << "n = " << n;
  }
}

}  // namespace
}  // namespace mechflow::bench
