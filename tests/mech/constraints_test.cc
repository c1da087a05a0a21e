// Closed loops: assembly, constrained accelerations, reactions, projection.
#include "mech/mechanism.h"

#include <cmath>

#include <gtest/gtest.h>

#include "mech/errors.h"
#include "tests/mech/mech_test_util.h"

namespace mechflow::mech {
namespace {

using testing::Et;
using T = TransformType;

// Planar four-bar in the y-z plane, hinges about x: ground pivots at y = 0 and
// y = d; crank a, coupler b, rocker c. Links are slender rods along their local
// y axis. The last joint closes the loop.
std::shared_ptr<const Model> FourBar(double a = 0.3, double b = 0.8, double c = 0.6, double d = 0.7) {
  ModelBuilder m;
  auto rod = [](const std::string& name, double length) {
    BodySpec s = testing::Box(name, 1.0 * length, {0.01, 0.5 * length, 0.01}, Vec3(0, 0.5 * length, 0));
    return s;
  };
  m.AddBody(rod("Crank", a));
  m.AddBody(rod("Coupler", b));
  m.AddBody(rod("Rocker", c));
  m.AddJoint(testing::ChainJoint("j1", "Base0", "Crank", {Et(T::kRv, Vec3::UnitX(), 1.2, 2.0)}));
  m.AddJoint(testing::ChainJoint("j2", "Crank", "Coupler",
                                 {Et(T::kTc, Vec3::UnitY(), a), Et(T::kRv, Vec3::UnitX(), -1.0)}));
  m.AddJoint(testing::ChainJoint("j3", "Base0", "Rocker",
                                 {Et(T::kTc, Vec3::UnitY(), d), Et(T::kRv, Vec3::UnitX(), 1.9)}));
  JointSpec close = testing::ChainJoint("j4", "Coupler", "Rocker",
                                        {Et(T::kTc, Vec3::UnitY(), b), Et(T::kRv, Vec3::UnitX())});
  close.frame2 = Pose::Translation(Vec3(0, c, 0));
  m.AddJoint(close);
  return m.Build();
}

double Energy(const Mechanism& mech, std::span<const double> x, MechanismWorkspace* ws) {
  const Model& model = mech.model();
  EvaluatePositions(mech, 0.0, x, ws);
  Eigen::MatrixXd M;
  MassMatrix(model, ws->kin, &M, &ws->dyn);
  const Eigen::Map<const Eigen::VectorXd> v(x.data() + model.nq(), model.nv());
  double e = 0.5 * v.dot(M * v);
  for (int b = 1; b < model.num_bodies(); ++b)
    e -= model.bodies()[b].mass * model.gravity().dot(PointPosition(ws->kin, b, model.bodies()[b].com));
  return e;
}

TEST(ConstraintsTest, FourBarAssemblesAndItsAccelerationsSatisfyTheConstraints) {
  Mechanism mech(FourBar(), {}, {});
  MechanismWorkspace ws(mech);
  std::vector<double> x(mech.num_states()), xdot(mech.num_states());
  InitialState(mech, {}, x, {}, &ws);
  const Model& model = mech.model();
  Eigen::VectorXd phi, psi;
  EvaluatePositions(mech, 0.0, x, &ws);
  mech.constraints().Residual(model, ws.kin, &phi);
  mech.constraints().VelocityResidual(model, ws.kin, &psi);
  EXPECT_LT(phi.lpNorm<Eigen::Infinity>(), 1e-12);
  EXPECT_LT(psi.lpNorm<Eigen::Infinity>(), 1e-12);
  // The crank angle the user gave is kept approximately; the loop has 1 DOF.
  Eigen::MatrixXd J;
  mech.constraints().Jacobian(model, ws.kin, &J);
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(J);
  EXPECT_EQ(model.nv() - cod.rank(), 1);
  EvaluateMechanism(mech, 0.0, x, {}, {}, &ws, xdot);
  // Acceleration-level constraint: the relative acceleration vanishes. Check by
  // differencing the velocity residual along the motion.
  const double h = 1e-6;
  std::vector<double> xp(x), xm(x);
  for (std::size_t i = 0; i < x.size(); ++i) {
    xp[i] += h * xdot[i];
    xm[i] -= h * xdot[i];
  }
  Eigen::VectorXd psi_p, psi_m;
  EvaluatePositions(mech, 0.0, xp, &ws);
  mech.constraints().VelocityResidual(model, ws.kin, &psi_p);
  EvaluatePositions(mech, 0.0, xm, &ws);
  mech.constraints().VelocityResidual(model, ws.kin, &psi_m);
  EXPECT_LT(((psi_p - psi_m) / (2 * h)).lpNorm<Eigen::Infinity>(), 1e-6);
}

TEST(ConstraintsTest, FourBarConservesEnergyWithProjection) {
  // Classical RK4 with projection after each step: an integrator independent
  // of CVODE, so the KKT dynamics is checked on its own.
  Mechanism mech(FourBar(), {}, {});
  MechanismWorkspace ws(mech);
  const Model& model = mech.model();
  const int n = mech.num_states();
  std::vector<double> x(n), k1(n), k2(n), k3(n), k4(n), tmp(n);
  InitialState(mech, {}, x, {}, &ws);
  const double e0 = Energy(mech, x, &ws);
  const double h = 1e-3;
  auto f = [&](const std::vector<double>& y, std::vector<double>* out) {
    EvaluateMechanism(mech, 0.0, y, {}, {}, &ws, *out);
  };
  double worst = 0.0;
  for (int step = 0; step < 2000; ++step) {
    f(x, &k1);
    for (int i = 0; i < n; ++i) tmp[i] = x[i] + 0.5 * h * k1[i];
    f(tmp, &k2);
    for (int i = 0; i < n; ++i) tmp[i] = x[i] + 0.5 * h * k2[i];
    f(tmp, &k3);
    for (int i = 0; i < n; ++i) tmp[i] = x[i] + h * k3[i];
    f(tmp, &k4);
    for (int i = 0; i < n; ++i) x[i] += h / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
    std::span<double> q(x.data(), model.nq()), v(x.data() + model.nq(), model.nv());
    ProjectPositions(model, mech.constraints(), 0.0, q, v, 1e-13, 10, &ws.kin, &ws.constraint);
    ProjectVelocities(model, mech.constraints(), 0.0, q, v, &ws.kin, &ws.constraint);
    worst = std::max(worst, std::abs(Energy(mech, x, &ws) - e0));
  }
  EXPECT_LT(worst / std::abs(e0), 1e-6) << "energy " << e0;
}

TEST(ConstraintsTest, ALoopThatConstrainsNothingMovableLeavesTheBodyAtRest) {
  // Two welds of one body to the base: the second closes a loop whose
  // Jacobian is zero. The projections and the dynamics once read a step sized
  // for no rows at all (a crash found by fuzzing the scene builder).
  ModelBuilder m;
  m.AddBody(testing::Box("B", 1.0, {0.1, 0.1, 0.1}, Vec3::Zero()));
  m.AddJoint(testing::ChainJoint("weld1", "Base0", "B", {}));
  m.AddJoint(testing::ChainJoint("weld2", "Base0", "B", {}));
  Mechanism mech(m.Build(), {}, {});
  MechanismWorkspace ws(mech);
  std::vector<double> x(mech.num_states()), xdot(mech.num_states(), 1.0);
  InitialState(mech, {}, x, {}, &ws);
  EvaluateMechanism(mech, 0.0, x, {}, {}, &ws, xdot);
  for (double d : xdot) EXPECT_EQ(d, 0.0);
}

TEST(ConstraintsTest, ReactionsBalanceAHangingBodyAndACutJoint) {
  // A body hanging from two hinges on the same axis: the second closes a
  // loop with fully redundant equations. Together the reactions carry m g.
  ModelBuilder m;
  m.AddBody(testing::Box("Bar", 2.0, {0.5, 0.05, 0.05}, Vec3(0, 0, -0.3)));
  m.AddJoint(testing::ChainJoint("left", "Base0", "Bar", {Et(T::kRv, Vec3::UnitX())}));
  JointSpec right = testing::ChainJoint("right", "Base0", "Bar", {Et(T::kTc, Vec3::UnitX(), 0.4),
                                                                  Et(T::kRv, Vec3::UnitX())});
  right.frame2 = Pose::Translation(Vec3(0.4, 0, 0));
  m.AddJoint(right);
  Mechanism mech(m.Build(), {}, {});
  MechanismWorkspace ws(mech);
  std::vector<double> x(mech.num_states()), xdot(mech.num_states());
  InitialState(mech, {}, x, {}, &ws);
  EvaluateMechanism(mech, 0.0, x, {}, {}, &ws, xdot);
  EXPECT_NEAR(xdot[1], 0.0, 1e-12);
  const Wrench left = JointReaction(mech, ws, 0), cut = JointReaction(mech, ws, 1);
  EXPECT_NEAR((left.force + cut.force).z(), 2.0 * 9.81, 1e-9);
  EXPECT_NEAR((left.force + cut.force).head<2>().norm(), 0.0, 1e-9);
}

TEST(ConstraintsTest, ALoopThatCannotCloseIsAnInputError) {
  ModelBuilder m;
  m.AddBody(testing::Box("A", 1.0, {0.1, 0.1, 0.1}));
  m.AddJoint(testing::ChainJoint("j1", "Base0", "A", {Et(T::kRv, Vec3::UnitX())}));
  JointSpec far = testing::ChainJoint("j2", "Base0", "A", {Et(T::kTc, Vec3::UnitY(), 5.0)});
  far.origin = "m.xml:9";
  m.AddJoint(far);
  Mechanism mech(m.Build(), {}, {});
  MechanismWorkspace ws(mech);
  std::vector<double> x(mech.num_states());
  try {
    InitialState(mech, {}, x, {}, &ws);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("m.xml:9: the loop closed by joint 'j2' cannot be assembled"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace mechflow::mech

namespace mechflow::mech {
namespace {

TEST(ConstraintsTest, TwoHingesOnCrossedAxesAreOverConstrained) {
  ModelBuilder m;
  m.AddBody(testing::Box("Door", 1.0, {0.1, 0.1, 0.1}));
  m.AddJoint(testing::ChainJoint("hinge", "Base0", "Door", {testing::Et(TransformType::kRv, Vec3::UnitX())}));
  JointSpec other = testing::ChainJoint("other", "Base0", "Door", {testing::Et(TransformType::kRv, Vec3::UnitY())});
  other.origin = "m.xml:12";
  m.AddJoint(other);
  Mechanism mech(m.Build(), {}, {});
  MechanismWorkspace ws(mech);
  std::vector<double> x(mech.num_states());
  try {
    InitialState(mech, {}, x, {}, &ws);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("m.xml:12: joint 'other' over-constrains the mechanism: with it, bodies "
                                         "'Door' have no degree of freedom left"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace mechflow::mech

namespace mechflow::mech {
namespace {

// A decaying torque F0 exp(-mu t) on one coordinate (test-only element).
class DecayingTorque final : public ForceElement {
 public:
  DecayingTorque(int v_index, double f0, double mu) : ForceElement("torque", ""), v_(v_index), f0_(f0), mu_(mu) {}
  void Evaluate(const ElementContext& ctx, Loads* loads, std::span<double>, std::span<double>) const override {
    loads->AddGeneralizedForce(v_, f0_ * std::exp(-mu_ * ctx.t));
  }

 private:
  int v_;
  double f0_, mu_;
};

TEST(ConstraintsTest, Convel1ShaftsTurnTogetherAsCV1) {
  // ELEMENTS.md 9.4 / CV-1: shaft 1 about global Y, shaft 2 inclined by alpha
  // on a revolute about its own Y, joined by a CV joint at (0, 0.5, 0): three
  // of its four equations repeat the revolute (redundant).
  const double alpha = 10.0 * M_PI / 180.0, f0 = 0.01, mu = 0.1;
  ModelBuilder m;
  BodySpec shaft1 = testing::Box("Body1", 10.0, {0.1, 0.25, 0.1});
  shaft1.inertia = Vec3(5.0, 0.1, 5.0).asDiagonal();
  BodySpec shaft2 = shaft1;
  shaft2.name = "Body2";
  m.AddBody(shaft1);
  m.AddBody(shaft2);
  m.AddJoint(testing::ChainJoint("jBody1", "Base0", "Body1", {Et(T::kRv, Vec3::UnitY())}));
  TransformSpec tilt = Et(T::kRt, Vec3::UnitX());
  tilt.function = std::make_shared<ConstantTimeFunction>(alpha);
  m.AddJoint(testing::ChainJoint("jBody2", "Base0", "Body2",
                                 {Et(T::kTc, Vec3(0, 0.5, 0), 0.5), tilt, Et(T::kRv, Vec3::UnitY())}));
  JointSpec cv;
  cv.name = "cv";
  cv.body1 = "Body1";
  cv.body2 = "Body2";
  cv.convel = true;
  cv.frame1 = Pose::Translation(Vec3(0, 0.5, 0));
  cv.convel_axis1 = Vec3::UnitY();
  cv.convel_axis2 = Vec3::UnitY();
  m.AddJoint(cv);
  std::vector<std::unique_ptr<ForceElement>> elements;
  elements.push_back(std::make_unique<DecayingTorque>(0, f0, mu));
  Mechanism mech(m.Build(), std::move(elements), {});
  MechanismWorkspace ws(mech);
  const Model& model = mech.model();
  const int n = mech.num_states();
  std::vector<double> x(n), k1(n), k2(n), k3(n), k4(n), tmp(n);
  InitialState(mech, {}, x, {}, &ws);
  const double h = 5e-3;
  double t = 0.0, worst_difference = 0.0;
  auto f = [&](double time, const std::vector<double>& y, std::vector<double>* out) {
    EvaluateMechanism(mech, time, y, {}, {}, &ws, *out);
  };
  for (int step = 0; step < 2000; ++step) {
    f(t, x, &k1);
    for (int i = 0; i < n; ++i) tmp[i] = x[i] + 0.5 * h * k1[i];
    f(t + 0.5 * h, tmp, &k2);
    for (int i = 0; i < n; ++i) tmp[i] = x[i] + 0.5 * h * k2[i];
    f(t + 0.5 * h, tmp, &k3);
    for (int i = 0; i < n; ++i) tmp[i] = x[i] + h * k3[i];
    f(t + h, tmp, &k4);
    for (int i = 0; i < n; ++i) x[i] += h / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
    t += h;
    std::span<double> q(x.data(), model.nq()), v(x.data() + model.nq(), model.nv());
    ProjectPositions(model, mech.constraints(), t, q, v, 1e-13, 10, &ws.kin, &ws.constraint);
    ProjectVelocities(model, mech.constraints(), t, q, v, &ws.kin, &ws.constraint);
    worst_difference = std::max(worst_difference, std::abs(v[0] - v[1]));
  }
  const double expected = f0 / (mu * 0.2) * (1.0 - std::exp(-mu * 10.0));
  EXPECT_NEAR(expected, 0.316060, 1e-6);
  EXPECT_NEAR(x[model.nq()], expected, 1e-8);
  EXPECT_NEAR(x[model.nq() + 1], expected, 1e-8);
  EXPECT_LT(worst_difference, 1e-10);
}

TEST(ConstraintsTest, TwistResidualVanishesOnlyForEqualShaftAngles) {
  // Two shafts on fixed bearings 30 deg apart: the zero-twist row holds
  // exactly when both have turned by the same angle (ELEMENTS.md 2.5 proof).
  const double alpha = 30.0 * M_PI / 180.0;
  ModelBuilder m;
  BodySpec shaft1 = testing::Box("S1", 1.0, {0.05, 0.25, 0.05});
  BodySpec shaft2 = shaft1;
  shaft2.name = "S2";
  m.AddBody(shaft1);
  m.AddBody(shaft2);
  m.AddJoint(testing::ChainJoint("j1", "Base0", "S1", {Et(T::kRv, Vec3::UnitY(), 0.0, 1.0)}));
  // Shaft 2: fixed inclined bearing, spinning about its own axis.
  m.AddJoint(testing::ChainJoint("j2", "Base0", "S2",
                                 {Et(T::kTc, Vec3::UnitY(), 0.5), Et(T::kRc, Vec3::UnitX(), alpha),
                                  Et(T::kRv, Vec3::UnitY(), 0.0, 1.0)}));
  JointSpec cv;
  cv.name = "cv";
  cv.body1 = "S1";
  cv.body2 = "S2";
  cv.convel = true;
  cv.frame1 = Pose::Translation(Vec3(0, 0.5, 0));
  cv.convel_axis1 = Vec3::UnitY();
  cv.convel_axis2 = Vec3::UnitY();
  m.AddJoint(cv);
  Mechanism mech(m.Build(), {}, {});
  MechanismWorkspace ws(mech);
  std::vector<double> x(mech.num_states()), xdot(mech.num_states());
  InitialState(mech, {}, x, {}, &ws);
  // Rotate shaft 1 by a quarter turn, shaft 2 by the same angle: the twist
  // residual stays zero (homokinetic), while a different angle violates it.
  Eigen::VectorXd phi;
  for (double angle : {0.3, 0.785, 1.5}) {
    x[0] = angle;
    x[1] = angle;
    EvaluatePositions(mech, 0.0, x, &ws);
    mech.constraints().Residual(mech.model(), ws.kin, &phi);
    EXPECT_NEAR(phi(3), 0.0, 1e-12) << angle;
    x[1] = angle + 0.1;
    EvaluatePositions(mech, 0.0, x, &ws);
    mech.constraints().Residual(mech.model(), ws.kin, &phi);
    EXPECT_GT(std::abs(phi(3)), 1e-3) << angle;
  }
}

}  // namespace
}  // namespace mechflow::mech
