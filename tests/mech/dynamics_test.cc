// The three recursive algorithms checked against each other and against
// closed forms (ELEMENTS.md J-1, J-2, J-3 kinematics).
#include "mech/dynamics.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "mech/errors.h"
#include "tests/mech/mech_test_util.h"

namespace mechflow::mech {
namespace {

using testing::Et;
using testing::MixedTree;
using T = TransformType;

TEST(DynamicsTest, ForwardAndInverseDynamicsAgreeOnRandomStates) {
  const auto model = MixedTree();
  Kinematics kin(*model);
  DynamicsWorkspace ws(*model);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  std::vector<Vec6> external(model->segments().size());
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<double> q, v;
    testing::RandomState(*model, &rng, &q, &v);
    UpdateKinematics(*model, 0.0, q, v, &kin);
    std::vector<double> tau(model->nv()), vdot(model->nv()), tau_back(model->nv());
    for (double& x : tau) x = u(rng);
    for (auto& f : external)
      for (int k = 0; k < 6; ++k) f(k) = u(rng);
    ForwardDynamics(*model, kin, tau, external, vdot, &ws);
    InverseDynamics(*model, kin, vdot, external, tau_back, &ws);
    for (int i = 0; i < model->nv(); ++i) EXPECT_NEAR(tau_back[i], tau[i], 1e-12 * (1 + std::abs(tau[i]))) << i;
  }
}

TEST(DynamicsTest, MassMatrixMatchesInverseDynamicsColumns) {
  const auto model = MixedTree();
  Kinematics kin(*model);
  DynamicsWorkspace ws(*model);
  std::mt19937 rng(11);
  std::vector<double> q, v;
  testing::RandomState(*model, &rng, &q, &v);
  UpdateKinematics(*model, 0.0, q, v, &kin);
  Eigen::MatrixXd M;
  MassMatrix(*model, kin, &M, &ws);
  const int n = model->nv();
  std::vector<Vec6> none(model->segments().size(), Vec6::Zero());
  // M e_k = ID(e_k) - ID(0) with the same velocities and no gravity-free
  // trick needed: the bias cancels in the difference.
  std::vector<double> zero(n, 0.0), h(n), col(n);
  InverseDynamics(*model, kin, zero, none, h, &ws);
  for (int k = 0; k < n; ++k) {
    std::vector<double> e(n, 0.0);
    e[k] = 1.0;
    InverseDynamics(*model, kin, e, none, col, &ws);
    for (int i = 0; i < n; ++i) EXPECT_NEAR(M(i, k), col[i] - h[i], 1e-12) << i << "," << k;
  }
  EXPECT_LT((M - M.transpose()).norm(), 1e-14);
  EXPECT_GT(M.llt().info() == Eigen::Success ? 1 : 0, 0) << "mass matrix must be positive definite";
}

TEST(DynamicsTest, ConvelChainPlacesTheShaftEndAsJ1) {
  // ELEMENTS.md J-1: tc(0,0.5,0), rt X by alpha = 10 deg, rv Y at 0.7 rad.
  ModelBuilder b;
  b.AddBody(testing::Box("Body2", 10.0, {0.05, 0.5, 0.05}));
  TransformSpec tilt = Et(T::kRt, Vec3::UnitX());
  tilt.function = std::make_shared<ConstantTimeFunction>(10.0 * M_PI / 180.0);
  b.AddJoint(testing::ChainJoint("j", "Base0", "Body2",
                                 {Et(T::kTc, Vec3(0, 0.5, 0), 0.5), tilt, Et(T::kRv, Vec3::UnitY(), 0.7)}));
  const auto model = b.Build();
  Kinematics kin(*model);
  std::vector<double> q = model->initial_q(), v = model->initial_v();
  UpdateKinematics(*model, 0.0, q, v, &kin);
  const Vec3 p = PointPosition(kin, 1, Vec3(0, 0.5, 0));
  EXPECT_NEAR(p.x(), 0.0, 1e-6);
  EXPECT_NEAR(p.y(), 0.992404, 1e-6);
  EXPECT_NEAR(p.z(), 0.086824, 1e-6);
}

TEST(DynamicsTest, CardanChainRotationIsJ2) {
  ModelBuilder b;
  b.AddBody(testing::Box("A", 1.0, {0.1, 0.1, 0.1}));
  b.AddJoint(testing::ChainJoint(
      "j", "Base0", "A",
      {Et(T::kRv, Vec3::UnitX(), 0.1), Et(T::kRv, Vec3::UnitY(), 0.2), Et(T::kRv, Vec3::UnitZ(), 0.3)}));
  const auto model = b.Build();
  Kinematics kin(*model);
  UpdateKinematics(*model, 0.0, model->initial_q(), model->initial_v(), &kin);
  Mat3 expected;
  expected << 0.936293, -0.289629, 0.198669, 0.312992, 0.944702, -0.097843, -0.159345, 0.153792, 0.975170;
  EXPECT_LT((kin.body_pose[1].R - expected).cwiseAbs().maxCoeff(), 1e-6);
  const Eigen::Quaterniond quat(kin.body_pose[1].R);
  EXPECT_NEAR(std::abs(quat.w()), 0.981856, 1e-6);
  EXPECT_NEAR(std::abs(quat.z()), 0.153439, 1e-6);
}

TEST(DynamicsTest, PointAccelerationMatchesFiniteDifferenceOfVelocity) {
  // Independent check of the acceleration bookkeeping: integrate one tiny
  // step by hand and difference the point velocity.
  const auto model = MixedTree();
  Kinematics kin(*model), kin2(*model);
  DynamicsWorkspace ws(*model);
  std::mt19937 rng(3);
  std::vector<double> q, v;
  testing::RandomState(*model, &rng, &q, &v);
  std::vector<double> tau(model->nv(), 0.0), vdot(model->nv()), qdot(model->nq());
  std::vector<Vec6> none(model->segments().size(), Vec6::Zero());
  UpdateKinematics(*model, 0.0, q, v, &kin);
  ForwardDynamics(*model, kin, tau, none, vdot, &ws);
  const double h = 1e-6;
  auto state_at = [&](double dt, std::vector<double>* qq, std::vector<double>* vv) {
    CoordinateRates(*model, q, v, qdot);
    qq->resize(q.size());
    vv->resize(v.size());
    for (std::size_t i = 0; i < q.size(); ++i) (*qq)[i] = q[i] + dt * qdot[i];
    for (std::size_t i = 0; i < v.size(); ++i) (*vv)[i] = v[i] + dt * vdot[i];
  };
  std::vector<double> qp, vp, qm, vm;
  state_at(h, &qp, &vp);
  state_at(-h, &qm, &vm);
  for (int body = 1; body < model->num_bodies(); ++body) {
    const Vec3 point(0.1, -0.2, 0.3);
    UpdateKinematics(*model, 0.0, qp, vp, &kin2);
    const Vec3 vplus = PointVelocity(kin2, body, point);
    UpdateKinematics(*model, 0.0, qm, vm, &kin2);
    const Vec3 vminus = PointVelocity(kin2, body, point);
    const Vec3 fd = (vplus - vminus) / (2 * h);
    const Vec3 a = PointAcceleration(*model, kin, ws, body, point);
    EXPECT_LT((fd - a).norm(), 1e-5 * (1 + a.norm())) << model->bodies()[body].name;
  }
}

TEST(DynamicsTest, BadBodiesAndJointsAreInputErrors) {
  auto error_of = [](auto&& fn) -> std::string {
    try {
      fn();
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  };
  BodySpec light = testing::Box("L", 1.0, {0.1, 0.1, 0.1});
  light.mass = 0.0;
  light.origin = "m.xml:3";
  EXPECT_EQ(error_of([&] { ModelBuilder().AddBody(light); }),
            "m.xml:3: body 'L': mass must be a positive number of kg (got 0)");
  BodySpec odd = testing::Box("O", 1.0, {0.1, 0.1, 0.1});
  odd.inertia = Vec3(1.0, 1.0, 3.0).asDiagonal();
  EXPECT_NE(error_of([&] { ModelBuilder().AddBody(odd); }).find("triangle inequality"), std::string::npos);
  odd.inertia = Vec3(1.0, -1.0, 1.0).asDiagonal();
  EXPECT_NE(error_of([&] { ModelBuilder().AddBody(odd); }).find("positive semi-definite"), std::string::npos);
  EXPECT_NE(error_of([&] {
              ModelBuilder b;
              b.AddBody(testing::Box("A", 1.0, {0.1, 0.1, 0.1}));
              b.AddJoint(testing::ChainJoint("j", "Base0", "Aa", {Et(T::kRv, Vec3::UnitX())}));
            }).find("unknown body 'Aa'"),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              ModelBuilder b;
              b.AddBody(testing::Box("A", 1.0, {0.1, 0.1, 0.1}));
              b.AddJoint(testing::ChainJoint("j", "Base0", "A", {Et(T::kRv, Vec3::Zero())}));
            }).find("axis vector must be non-zero"),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              ModelBuilder b;
              b.AddBody(testing::Box("A", 1.0, {0.1, 0.1, 0.1}));
              b.AddBody(testing::Box("B", 1.0, {0.1, 0.1, 0.1}));
              b.AddJoint(testing::ChainJoint("j", "Base0", "A", {Et(T::kRv, Vec3::UnitX())}));
              b.Build();
            }).find("body 'B' is not connected to Base0"),
            std::string::npos);
}

}  // namespace
}  // namespace mechflow::mech
