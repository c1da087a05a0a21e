// Friction fed from a joint reaction force (diagrams/examples/
// cart_pendulum_friction.xml): an algebraic loop solved at every evaluation,
// against the Lagrange equations of the cart and rod integrated here.

#include <cmath>
#include <string>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "blocks/solver/simulator.h"
#include "diagrams/loader.h"

namespace mechflow {
namespace {

// Cart (mass mc) at x on a rail, uniform rod (mass mr, length L) hinged to it
// at its top end at angle theta from hanging. With a = L/2, J = mr L^2/3:
//   (mc + mr) x'' + mr a (cos th th'' - sin th th'^2) = F
//   mr a cos th x'' + J th'' + mr g a sin th = 0
//   N = (mc + mr) g + mr a (sin th th'' + cos th th'^2)   (vertical balance)
//   F = -mu N sign(x')
// which is linear in (x'', th'', N) once the sign of x' is known: the loop
// solved exactly, independently of the diagram's Newton iteration.
struct CartRod {
  double mc = 1, mr = 2, L = 1, mu = 0.3, g = 9.81;

  // (x'', th'', N) at state (x, v, th, w).
  Eigen::Vector3d Solve(const Eigen::Vector4d& s) const {
    const double a = L / 2, J = mr * L * L / 3, th = s[2], w = s[3];
    const double sign = s[1] > 0 ? 1.0 : -1.0;
    Eigen::Matrix3d A;
    Eigen::Vector3d b;
    A << mc + mr, mr * a * std::cos(th), mu * sign,  //
        mr * a * std::cos(th), J, 0.0,                //
        0.0, -mr * a * std::sin(th), 1.0;
    b << mr * a * std::sin(th) * w * w, -mr * g * a * std::sin(th), (mc + mr) * g + mr * a * std::cos(th) * w * w;
    return A.partialPivLu().solve(b);
  }
  Eigen::Vector4d Rate(const Eigen::Vector4d& s) const {
    const Eigen::Vector3d acc = Solve(s);
    return {s[1], acc[0], s[3], acc[1]};
  }
};

TEST(AlgebraicLoopExampleTest, ReactionForceFrictionMatchesLagrange) {
  diagrams::LoadOptions options;
  const auto loaded =
      diagrams::LoadDiagram(std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/cart_pendulum_friction.xml", options);
  ASSERT_EQ(loaded.diagram->loops().size(), 1u);
  blocks::Simulator sim(*loaded.diagram, loaded.solver, loaded.logged);
  const blocks::RunOutcome outcome = sim.Run();
  ASSERT_TRUE(outcome.ok) << outcome.failure;
  const blocks::Results& r = sim.results();
  auto column = [&](const std::string& name) { return r.Column(r.FindColumn(name)); };
  const auto t = column("time"), x = column("m.x"), v = column("m.v"), th = column("m.theta"), N = column("normal force"),
             F = column("friction force");

  // RK4 at 1e-5 s: its error (~1e-15 per unit time) is far below the bounds.
  const CartRod ref;
  Eigen::Vector4d s(0.0, 2.0, 0.0, 0.0);
  const double h = 1e-5;
  double time = 0.0, worst_x = 0.0, worst_th = 0.0, worst_N = 0.0, worst_loop = 0.0;
  double N_min = 1e9, N_max = -1e9;
  for (std::size_t i = 0; i < t.size(); ++i) {
    while (time < t[i] - 0.5 * h) {
      const Eigen::Vector4d k1 = ref.Rate(s), k2 = ref.Rate(s + 0.5 * h * k1), k3 = ref.Rate(s + 0.5 * h * k2),
                            k4 = ref.Rate(s + h * k3);
      s += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
      time += h;
    }
    const double N_ref = ref.Solve(s)[2];
    worst_x = std::max(worst_x, std::abs(x[i] - s[0]));
    // The rod angle's sign follows the hinge axis; the physics does not.
    worst_th = std::max(worst_th, std::abs(std::abs(th[i]) - std::abs(s[2])));
    worst_N = std::max(worst_N, std::abs(N[i] - N_ref));
    // The loop holds: F = -mu N at every output (the cart never stops here).
    worst_loop = std::max(worst_loop, std::abs(F[i] + ref.mu * N[i]));
    N_min = std::min(N_min, N[i]);
    N_max = std::max(N_max, N[i]);
    ASSERT_GT(v[i], 0.1);
  }
  EXPECT_LT(worst_x, 1e-7);
  EXPECT_LT(worst_th, 1e-7);
  EXPECT_LT(worst_N, 1e-5);  // N ~ 30 N
  EXPECT_LT(worst_loop, 1e-8);
  // The reaction really varies with the swing: the loop is not trivial.
  EXPECT_GT(N_max - N_min, 1.0);
  const blocks::LoopStats& stats = loaded.diagram->loops()[0].stats(sim.context());
  EXPECT_GT(stats.solves, 0);
  EXPECT_LT(double(stats.iterations) / stats.solves, 2.0);
  std::printf("N in [%.4f, %.4f] N; max errors x %.2e m, theta %.2e rad, N %.2e N; loop %.2e N; "
              "%ld solves, %.3f iterations/solve, %ld Jacobians\n",
              N_min, N_max, worst_x, worst_th, worst_N, worst_loop, stats.solves,
              double(stats.iterations) / stats.solves, stats.jacobians);
}

}  // namespace
}  // namespace mechflow
