// The quaternion joint (ELEMENTS.md 2.4, test J-3).
#include <functional>
#include <cmath>

#include <gtest/gtest.h>

#include "mech/mechanism.h"
#include "tests/mech/mech_test_util.h"

namespace mechflow::mech {
namespace {

std::shared_ptr<const Model> FreeBody(const Vec3& inertia, const Vec3& omega0, const Vec3& gravity) {
  ModelBuilder m;
  m.SetGravity(gravity);
  BodySpec body = testing::Box("B", 1.0, {0.1, 0.1, 0.1});
  body.inertia = inertia.asDiagonal();
  m.AddBody(body);
  JointSpec j;
  j.name = "free";
  j.body1 = "Base0";
  j.body2 = "B";
  j.quaternion = true;
  j.quaternion_initial.angular_velocity = omega0;
  m.AddJoint(j);
  return m.Build();
}

// Classical RK4 on the mechanism, quaternion renormalised after each step.
void Integrate(const Mechanism& mech, MechanismWorkspace* ws, std::vector<double>* x, double t_end, int steps,
               const std::function<void(const std::vector<double>&)>& after_step = {}) {
  const int n = mech.num_states();
  std::vector<double> k1(n), k2(n), k3(n), k4(n), tmp(n);
  const double h = t_end / steps;
  double t = 0.0;
  auto f = [&](double time, const std::vector<double>& y, std::vector<double>* out) {
    EvaluateMechanism(mech, time, y, {}, {}, ws, *out);
  };
  for (int s = 0; s < steps; ++s) {
    f(t, *x, &k1);
    for (int i = 0; i < n; ++i) tmp[i] = (*x)[i] + 0.5 * h * k1[i];
    f(t + 0.5 * h, tmp, &k2);
    for (int i = 0; i < n; ++i) tmp[i] = (*x)[i] + 0.5 * h * k2[i];
    f(t + 0.5 * h, tmp, &k3);
    for (int i = 0; i < n; ++i) tmp[i] = (*x)[i] + h * k3[i];
    f(t + h, tmp, &k4);
    for (int i = 0; i < n; ++i) (*x)[i] += h / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
    t += h;
    Eigen::Map<Eigen::Vector4d>(x->data() + 3).normalize();
    if (after_step) after_step(*x);
  }
}

TEST(QuaternionJointTest, ConstantSpinGivesTheExactRotation) {
  Mechanism mech(FreeBody(Vec3(1, 1, 1), Vec3(0, 0, 1), Vec3::Zero()), {}, {});
  MechanismWorkspace ws(mech);
  std::vector<double> x(mech.num_states());
  InitialState(mech, {}, x, {}, &ws);
  Integrate(mech, &ws, &x, M_PI / 2, 2000);
  EvaluatePositions(mech, 0.0, x, &ws);
  const Mat3 expected = AxisRotation(Vec3::UnitZ(), M_PI / 2);
  EXPECT_LT((ws.kin.body_pose[1].R - expected).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(QuaternionJointTest, TumblingBodyKeepsEnergyAndAngularMomentum) {
  // Spin near the unstable middle axis: the body flips over, yet kinetic
  // energy and |angular momentum| stay put (J-3; 1e-8 relative).
  const Vec3 inertia(1, 2, 3);
  Mechanism mech(FreeBody(inertia, Vec3(0.01, 1, 0), Vec3::Zero()), {}, {});
  MechanismWorkspace ws(mech);
  std::vector<double> x(mech.num_states());
  InitialState(mech, {}, x, {}, &ws);
  auto invariants = [&](const std::vector<double>& y, double* energy, double* momentum) {
    const Vec3 w(y[7], y[8], y[9]);  // body axes
    *energy = 0.5 * w.dot(inertia.cwiseProduct(w));
    *momentum = inertia.cwiseProduct(w).norm();
  };
  double e0, l0;
  invariants(x, &e0, &l0);
  double worst_e = 0, worst_l = 0, min_wy = 1;
  Integrate(mech, &ws, &x, 30.0, 30000, [&](const std::vector<double>& y) {
    double e, l;
    invariants(y, &e, &l);
    worst_e = std::max(worst_e, std::abs(e - e0) / e0);
    worst_l = std::max(worst_l, std::abs(l - l0) / l0);
    min_wy = std::min(min_wy, y[8]);
  });
  EXPECT_LT(worst_e, 1e-8);
  EXPECT_LT(worst_l, 1e-8);
  EXPECT_LT(min_wy, -0.9) << "the body should have flipped (spin about -y)";
}

TEST(QuaternionJointTest, FallingBodyHasFreeFallKinematics) {
  Mechanism mech(FreeBody(Vec3(1, 2, 3), Vec3(0.3, -0.2, 0.5), Vec3(0, 0, -9.81)), {}, {});
  MechanismWorkspace ws(mech);
  std::vector<double> x(mech.num_states());
  InitialState(mech, {}, x, {}, &ws);
  Integrate(mech, &ws, &x, 1.0, 1000);
  EXPECT_NEAR(x[2], -0.5 * 9.81, 1e-9);
  EXPECT_NEAR(x[0], 0.0, 1e-12);
}

}  // namespace
}  // namespace mechflow::mech
