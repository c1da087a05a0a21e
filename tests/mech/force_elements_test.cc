// Force elements against hand computation (ELEMENTS.md 3.1-3.4, 4).
#include <cmath>

#include <gtest/gtest.h>

#include "mech/applied_force.h"
#include "mech/bipolar_force.h"
#include "mech/bushing.h"
#include "mech/errors.h"
#include "mech/joint_force.h"
#include "mech/mechanism.h"
#include "tests/mech/mech_test_util.h"

namespace mechflow::mech {
namespace {

using testing::Et;
using T = TransformType;

// A 10 kg box on a vertical translational joint, gravity off.
std::shared_ptr<const Model> Slider(double z0) {
  ModelBuilder m;
  m.SetGravity(Vec3::Zero());
  m.AddBody(testing::Box("Box", 10.0, {0.1, 0.1, 0.1}));
  m.AddJoint(testing::ChainJoint("j", "Base0", "Box", {Et(T::kTv, Vec3::UnitZ(), z0)}));
  return m.Build();
}

// v' of the box under the given elements at its initial state.
double Acceleration(std::shared_ptr<const Model> model, std::vector<std::unique_ptr<ForceElement>> elements,
                    std::vector<double>* sensors = nullptr) {
  Mechanism mech(model, std::move(elements), {});
  MechanismWorkspace ws(mech);
  std::vector<double> x(mech.num_states()), xdot(mech.num_states());
  InitialState(mech, {}, x, {}, &ws);
  EvaluateMechanism(mech, 0.0, x, {}, {}, &ws, xdot);
  if (sensors) *sensors = ws.sensors;
  return xdot[mech.model().nq()];
}

TEST(ForceElementsTest, PointsTableEqualsLinearSpringAsF2) {
  const PointsLaw table({-1, 0, 1}, {500, 0, -500}, PointsLaw::Interpolation::kLinear,
                        PointsLaw::Extrapolation::kLinear, 0.0, "m.xml:4");
  const LinearLaw linear(500.0, 0.0, 0.0, 0.0);
  ElementContext ctx;
  for (double x : {-2.5, -1.0, -0.3, 0.0, 0.2, 1.0, 3.0})
    EXPECT_NEAR(table.Force(x, 0.0, ctx), linear.Force(x, 0.0, ctx), 1e-12) << x;
  const PointsLaw clamped({-1, 0, 1}, {500, 0, -500}, PointsLaw::Interpolation::kLinear,
                          PointsLaw::Extrapolation::kClamp, 0.0, "");
  EXPECT_EQ(clamped.Table(3.0), -500.0);
}

TEST(ForceElementsTest, SplinePassesThroughThePointsWithContinuousSlope) {
  const PointsLaw spline({0, 1, 2, 4}, {0, 1, 0, 2}, PointsLaw::Interpolation::kSpline,
                         PointsLaw::Extrapolation::kLinear, 0.0, "");
  for (auto [x, f] : {std::pair{0.0, 0.0}, {1.0, 1.0}, {2.0, 0.0}, {4.0, 2.0}}) EXPECT_NEAR(spline.Table(x), f, 1e-12);
  const double h = 1e-6;
  for (double knot : {1.0, 2.0, 4.0}) {
    const double left = (spline.Table(knot) - spline.Table(knot - h)) / h;
    const double right = (spline.Table(knot + h) - spline.Table(knot)) / h;
    EXPECT_NEAR(left, right, 1e-4) << knot;
  }
}

TEST(ForceElementsTest, BadTablesAreInputErrors) {
  EXPECT_THROW(PointsLaw({0, 0}, {1, 2}, PointsLaw::Interpolation::kLinear, PointsLaw::Extrapolation::kLinear, 0.0,
                         "m.xml:5"),
               InputError);
  EXPECT_THROW(PointsLaw({0}, {1}, PointsLaw::Interpolation::kLinear, PointsLaw::Extrapolation::kLinear, 0.0, ""),
               InputError);
}

TEST(ForceElementsTest, BipolarRepulsionIsPositiveAndJointForceIncreasesQ) {
  // Spring between the ground point (0,0,2) and the box centre at z = 0.5:
  // compressed below its 2 m free length, so it pushes the box down.
  std::vector<std::unique_ptr<ForceElement>> e;
  e.push_back(std::make_unique<BipolarForce>("s", "", 0, Vec3(0, 0, 2), 1, Vec3::Zero(),
                                             std::make_unique<LinearLaw>(100.0, 2.0, 0.0, 0.0)));
  std::vector<double> sensors;
  EXPECT_NEAR(Acceleration(Slider(0.5), std::move(e), &sensors), -100.0 * 0.5 / 10.0, 1e-12);
  EXPECT_NEAR(sensors[0], 50.0, 1e-12);  // repulsion
  EXPECT_NEAR(sensors[1], 1.5, 1e-12);
  std::vector<std::unique_ptr<ForceElement>> j;
  j.push_back(std::make_unique<JointForce>("f", "", Slider(0.5)->dofs()[0],
                                           std::make_unique<LinearLaw>(0.0, 0.0, 0.0, 7.0)));
  EXPECT_NEAR(Acceleration(Slider(0.5), std::move(j)), 0.7, 1e-12);
}

TEST(ForceElementsTest, BushingHoldsTheSagOfBU1AndIsBalanced) {
  // BU-1: 10 kg on a bushing with only c_z = 39478.4 N/m: static sag m g / c_z.
  ModelBuilder m;
  m.AddBody(testing::Box("B", 10.0, {0.1, 0.1, 0.1}));
  JointSpec free;
  free.name = "free";
  free.body1 = "Base0";
  free.body2 = "B";
  free.quaternion = true;
  const double sag = 10.0 * 9.81 / 39478.4;
  free.quaternion_initial.position = Vec3(0, 0, -sag);
  m.AddJoint(free);
  auto model = m.Build();
  Kinematics kin(*model);
  std::vector<double> v0(model->nv(), 0.0);
  UpdateKinematics(*model, 0.0, model->initial_q(), v0, &kin);
  BushingParameters p;
  p.stiffness = {0, 0, 39478.4};
  // The bushing is neutral with the body at z = 0; the body starts at the sag.
  std::vector<std::unique_ptr<ForceElement>> e;
  e.push_back(std::make_unique<Bushing>("b", "", 0, Vec3::Zero(), 1, Vec3::Zero(), p, kin));
  Mechanism mech(model, std::move(e), {});
  MechanismWorkspace ws(mech);
  std::vector<double> x(mech.num_states()), xdot(mech.num_states());
  InitialState(mech, {}, x, {}, &ws);
  EvaluateMechanism(mech, 0.0, x, {}, {}, &ws, xdot);
  EXPECT_NEAR(sag, 2.485e-3, 1e-6);
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(xdot[model->nq() + i], 0.0, 1e-12) << i;
  EXPECT_NEAR(ws.sensors[2], 98.1, 1e-9);  // fz on body 2
  EXPECT_NEAR(std::sqrt(39478.4 / 10.0) / (2 * M_PI), 10.0, 1e-4);
}

}  // namespace
}  // namespace mechflow::mech
