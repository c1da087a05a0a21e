// Force elements against hand computation (ELEMENTS.md 0.1, 3.1-3.5, 4):
// the scalar laws alone, then each element's loads turned into generalized
// forces (by inverse dynamics with and without them) or accelerations (by the
// mechanism's forward dynamics). Algebra is checked to 1e-12 relative to the
// numbers involved; finite-difference slopes and gradients to the stated
// looser tolerances.
#include <array>
#include <cmath>
#include <random>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mech/applied_force.h"
#include "mech/bipolar_force.h"
#include "mech/bushing.h"
#include "mech/dynamics.h"
#include "mech/errors.h"
#include "mech/frictional_force.h"
#include "mech/joint_force.h"
#include "mech/mechanism.h"
#include "tests/mech/mech_test_util.h"

namespace mechflow::mech {
namespace {

using testing::Et;
using T = TransformType;
using Interp = PointsLaw::Interpolation;
using Extrap = PointsLaw::Extrapolation;

// ---------------------------------------------------------------------------
// Models and helpers

// A 10 kg box on a vertical translational joint, gravity off.
std::shared_ptr<const Model> Slider(double z0, double rate = 0.0) {
  ModelBuilder m;
  m.SetGravity(Vec3::Zero());
  m.AddBody(testing::Box("Box", 10.0, {0.1, 0.1, 0.1}));
  m.AddJoint(testing::ChainJoint("j", "Base0", "Box", {Et(T::kTv, Vec3::UnitZ(), z0, rate)}));
  return m.Build();
}

// A 10 kg box (0.2 m cube) turning about the global z axis through its centre.
std::shared_ptr<const Model> Turntable(double angle0) {
  ModelBuilder m;
  m.SetGravity(Vec3::Zero());
  m.AddBody(testing::Box("Box", 10.0, {0.1, 0.1, 0.1}));
  m.AddJoint(testing::ChainJoint("j", "Base0", "Box", {Et(T::kRv, Vec3::UnitZ(), angle0)}));
  return m.Build();
}

// Six coordinates x, y, z, then rotations about x, y, z: at zero x and y
// angles the generalized forces are the global force and the global moment
// about the body origin.
JointSpec Cardan(const std::string& name, const std::string& body1, const std::string& body2,
                 const std::array<double, 6>& q0 = {}) {
  return testing::ChainJoint(name, body1, body2,
                             {Et(T::kTv, Vec3::UnitX(), q0[0]), Et(T::kTv, Vec3::UnitY(), q0[1]),
                              Et(T::kTv, Vec3::UnitZ(), q0[2]), Et(T::kRv, Vec3::UnitX(), q0[3]),
                              Et(T::kRv, Vec3::UnitY(), q0[4]), Et(T::kRv, Vec3::UnitZ(), q0[5])});
}

// Two boxes A and B, each on its own Cardan chain from the ground.
std::shared_ptr<const Model> TwoCardanBodies(const std::array<double, 6>& qa, const std::array<double, 6>& qb) {
  ModelBuilder m;
  m.SetGravity(Vec3::Zero());
  m.AddBody(testing::Box("A", 2.0, {0.3, 0.2, 0.1}));
  m.AddBody(testing::Box("B", 3.0, {0.1, 0.2, 0.3}));
  m.AddJoint(Cardan("jA", "Base0", "A", qa));
  m.AddJoint(Cardan("jB", "Base0", "B", qb));
  return m.Build();
}

// Two free boxes on quaternion joints (centres of mass off the body origins).
std::shared_ptr<const Model> TwoFreeBodies() {
  ModelBuilder m;
  m.SetGravity(Vec3::Zero());
  m.AddBody(testing::Box("A", 2.0, {0.3, 0.2, 0.1}, {0.05, -0.02, 0.01}));
  m.AddBody(testing::Box("B", 3.0, {0.1, 0.2, 0.3}, {-0.03, 0.04, 0.02}));
  for (const char* body : {"A", "B"}) {
    JointSpec j;
    j.name = std::string("j") + body;
    j.body1 = "Base0";
    j.body2 = body;
    j.quaternion = true;
    m.AddJoint(j);
  }
  return m.Build();
}

// One element evaluated on its own at (t, q, v): its sensors and loads.
struct Probe {
  explicit Probe(std::shared_ptr<const Model> m) : model(std::move(m)), kin(*model), loads(*model) {}

  std::vector<double> Run(const ForceElement& element, std::span<const double> q, std::span<const double> v,
                          double t = 0.0, std::vector<double> args = {}) {
    UpdateKinematics(*model, t, q, v, &kin);
    loads.Clear();
    ElementContext ctx;
    ctx.t = t;
    ctx.model = model.get();
    ctx.kin = &kin;
    ctx.q = q;
    ctx.v = v;
    if (args.empty()) args = {t};
    parameter_args = std::move(args);
    ctx.parameter_args = parameter_args;
    std::vector<double> sensors(element.num_sensors(), 0.0);
    element.Evaluate(ctx, &loads, {}, sensors);
    return sensors;
  }
  std::vector<double> Run(const ForceElement& element) { return Run(element, model->initial_q(), model->initial_v()); }

  // Generalized forces of the last Run's loads: the difference of the inverse
  // dynamics without and with them (same accelerations), plus the loads'
  // own generalized forces.
  std::vector<double> Generalized() {
    DynamicsWorkspace ws(*model);
    std::vector<double> zero(model->nv(), 0.0), without(model->nv()), with(model->nv());
    const std::vector<Vec6> none(model->segments().size(), Vec6::Zero());
    InverseDynamics(*model, kin, zero, none, without, &ws);
    InverseDynamics(*model, kin, zero, loads.segment_loads(), with, &ws);
    std::vector<double> out(model->nv());
    for (int i = 0; i < model->nv(); ++i) out[i] = without[i] - with[i] + loads.generalized()[i];
    return out;
  }

  // Resultant of the segment loads about the global origin: [moment; force].
  Vec6 Resultant() const {
    Vec6 sum = Vec6::Zero();
    for (std::size_t s = 0; s < model->segments().size(); ++s) {
      const Vec6& w = loads.segment_loads()[s];
      const Vec3 f = kin.pose[s].R * w.tail<3>();
      sum.head<3>() += kin.pose[s].R * w.head<3>() + kin.pose[s].p.cross(f);
      sum.tail<3>() += f;
    }
    return sum;
  }

  std::shared_ptr<const Model> model;
  Kinematics kin;
  Loads loads;
  std::vector<double> parameter_args;
};

// v' of the first coordinate under the given elements at the model's initial
// state, through the mechanism (forward dynamics).
double Acceleration(std::shared_ptr<const Model> model, std::vector<std::unique_ptr<ForceElement>> elements,
                    std::vector<double>* sensors = nullptr, std::vector<std::string> input_names = {},
                    std::vector<double> inputs = {}, double t = 0.0) {
  Mechanism mech(model, std::move(elements), std::move(input_names));
  MechanismWorkspace ws(mech);
  std::vector<double> x(mech.num_states()), xdot(mech.num_states());
  InitialState(mech, inputs, x, {}, &ws);
  EvaluateMechanism(mech, t, x, inputs, {}, &ws, xdot);
  if (sensors) *sensors = ws.sensors;
  return xdot[mech.model().nq()];
}

std::vector<std::unique_ptr<ForceElement>> One(std::unique_ptr<ForceElement> e) {
  std::vector<std::unique_ptr<ForceElement>> out;
  out.push_back(std::move(e));
  return out;
}

// The InputError message `make` throws, or "" when it does not throw one.
template <typename F>
std::string InputErrorOf(F make) {
  try {
    make();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// f(args) = k * args[i]: reads one argument of a parameter or law.
class ArgumentTimes final : public ScalarFunction {
 public:
  ArgumentTimes(int i, double k) : i_(i), k_(k) {}
  double Evaluate(std::span<const double> args) const override { return k_ * args[i_]; }

 private:
  int i_;
  double k_;
};

// Records the arguments of its last call and returns a fixed combination of them.
class Recorder final : public ScalarFunction {
 public:
  double Evaluate(std::span<const double> args) const override {
    last.assign(args.begin(), args.end());
    double sum = 0.0;
    for (std::size_t i = 0; i < args.size(); ++i) sum += static_cast<double>(i + 1) * args[i];
    return sum;
  }
  mutable std::vector<double> last;
};

Parameter FunctionParameter(std::shared_ptr<const ScalarFunction> f, bool uses_inputs) {
  Parameter p;
  p.function = std::move(f);
  p.uses_inputs = uses_inputs;
  return p;
}

// ---------------------------------------------------------------------------
// Scalar laws

TEST(ForceLawTest, LinearIsRestoringAboutX0WithDampingAndOffset) {
  const LinearLaw law(500.0, 0.2, 30.0, 7.0);
  const ElementContext ctx;
  EXPECT_NEAR(law.Force(0.5, 0.1, ctx), -500.0 * 0.3 - 3.0 + 7.0, 1e-12);
  EXPECT_NEAR(law.Force(0.2, 0.0, ctx), 7.0, 1e-12);
  EXPECT_NEAR(law.Force(-0.1, -0.2, ctx), 150.0 + 6.0 + 7.0, 1e-12);
  EXPECT_FALSE(law.depends_on_inputs());
}

TEST(ForceLawTest, LinearParametersMayFollowTheInputs) {
  // c = 3 * input_0 (parameter arguments [t, inputs...]).
  const LinearLaw law(FunctionParameter(std::make_shared<ArgumentTimes>(1, 3.0), true), 0.0, 0.0, 0.0);
  EXPECT_TRUE(law.depends_on_inputs());
  const std::vector<double> args = {0.5, 4.0};
  ElementContext ctx;
  ctx.parameter_args = args;
  EXPECT_NEAR(law.Force(2.0, 0.0, ctx), -24.0, 1e-12);
}

TEST(ForceLawTest, PointsTableEqualsLinearSpringAsF2) {
  const PointsLaw table({-1, 0, 1}, {500, 0, -500}, Interp::kLinear, Extrap::kLinear, 0.0, "m.xml:4");
  const LinearLaw linear(500.0, 0.0, 0.0, 0.0);
  const ElementContext ctx;
  for (double x : {-2.5, -1.0, -0.3, 0.0, 0.2, 1.0, 3.0})
    EXPECT_NEAR(table.Force(x, 0.0, ctx), linear.Force(x, 0.0, ctx), 1e-12 * 500 * (1 + std::abs(x))) << x;
}

TEST(ForceLawTest, ExtrapolationLinearByDefaultOrClamped) {
  // Unequal end slopes: 2 on the left segment, 0.5 on the right one.
  const std::vector<double> xs = {0, 1, 3}, fs = {0, 2, 3};
  const PointsLaw linear(xs, fs, Interp::kLinear, Extrap::kLinear, 0.0, "");
  const PointsLaw clamp(xs, fs, Interp::kLinear, Extrap::kClamp, 0.0, "");
  EXPECT_NEAR(linear.Table(-1.0), -2.0, 1e-12);
  EXPECT_NEAR(linear.Table(5.0), 4.0, 1e-12);
  EXPECT_NEAR(linear.Table(2.0), 2.5, 1e-12);
  EXPECT_EQ(clamp.Table(-1.0), 0.0);
  EXPECT_EQ(clamp.Table(5.0), 3.0);
  EXPECT_NEAR(clamp.Table(0.5), 1.0, 1e-12);  // inside the table both agree
}

TEST(ForceLawTest, PointsViscousTermOpposesTheRate) {
  const PointsLaw law({0, 1}, {0, -10}, Interp::kLinear, Extrap::kLinear, 4.0, "");
  const ElementContext ctx;
  EXPECT_NEAR(law.Force(0.5, 2.0, ctx), -5.0 - 8.0, 1e-12);
  EXPECT_NEAR(law.Force(0.5, -2.0, ctx), -5.0 + 8.0, 1e-12);
}

TEST(ForceLawTest, SplinePassesThroughThePointsWithContinuousSlope) {
  const PointsLaw spline({0, 1, 2, 4}, {0, 1, 0, 2}, Interp::kSpline, Extrap::kLinear, 0.0, "");
  for (auto [x, f] : {std::pair{0.0, 0.0}, {1.0, 1.0}, {2.0, 0.0}, {4.0, 2.0}}) EXPECT_NEAR(spline.Table(x), f, 1e-12);
  // One-sided difference quotients at every knot, the end knots included
  // (where the linear extension takes over): equal to O(h).
  const double h = 1e-6;
  for (double knot : {0.0, 1.0, 2.0, 4.0}) {
    const double left = (spline.Table(knot) - spline.Table(knot - h)) / h;
    const double right = (spline.Table(knot + h) - spline.Table(knot)) / h;
    EXPECT_NEAR(left, right, 1e-4) << knot;
  }
  // Natural: no curvature at the ends.
  const double k = 1e-3;
  EXPECT_NEAR((spline.Table(0.0) - 2 * spline.Table(k) + spline.Table(2 * k)) / (k * k), 0.0, 0.05);
  EXPECT_NEAR((spline.Table(4.0) - 2 * spline.Table(4.0 - k) + spline.Table(4.0 - 2 * k)) / (k * k), 0.0, 0.05);
  // Not the broken line: between the knots it bends.
  EXPECT_GT(std::abs(spline.Table(0.5) - 0.5), 1e-3);
  // Beyond the ends: along the end tangent (linear) or held (clamp).
  const double slope_end = (spline.Table(4.0) - spline.Table(4.0 - h)) / h;
  EXPECT_NEAR(spline.Table(6.0), 2.0 + 2.0 * slope_end, 1e-5);
  const PointsLaw clamp({0, 1, 2, 4}, {0, 1, 0, 2}, Interp::kSpline, Extrap::kClamp, 0.0, "");
  EXPECT_EQ(clamp.Table(6.0), 2.0);
  EXPECT_EQ(clamp.Table(-1.0), 0.0);
  EXPECT_NEAR(clamp.Table(0.5), spline.Table(0.5), 1e-12);
}

TEST(ForceLawTest, TwoPointSplineIsTheStraightLine) {
  const PointsLaw spline({1, 3}, {2, -2}, Interp::kSpline, Extrap::kLinear, 0.0, "");
  for (double x : {0.0, 1.5, 2.0, 4.0}) EXPECT_NEAR(spline.Table(x), 2.0 - 2.0 * (x - 1.0), 1e-12) << x;
}

TEST(ForceLawTest, BadTablesAreInputErrorsNamingTheOrigin) {
  auto make = [](std::vector<double> x, std::vector<double> f) {
    return [x, f] { PointsLaw(x, f, Interp::kLinear, Extrap::kLinear, 0.0, "m.xml:5"); };
  };
  using ::testing::HasSubstr;
  using ::testing::StartsWith;
  EXPECT_THAT(InputErrorOf(make({0, 0}, {1, 2})), StartsWith("m.xml:5: "));
  EXPECT_THAT(InputErrorOf(make({0, 0}, {1, 2})), HasSubstr("increase strictly"));
  EXPECT_THAT(InputErrorOf(make({0, 2, 1}, {1, 2, 3})), AllOf(StartsWith("m.xml:5: "), HasSubstr("point 3")));
  EXPECT_THAT(InputErrorOf(make({0}, {1})), AllOf(StartsWith("m.xml:5: "), HasSubstr("at least two")));
  EXPECT_THAT(InputErrorOf(make({}, {})), StartsWith("m.xml:5: "));
  EXPECT_THAT(InputErrorOf(make({0, 1, 2}, {1, 2})), AllOf(StartsWith("m.xml:5: "), HasSubstr("as many")));
  EXPECT_THAT(InputErrorOf(make({0, NAN}, {1, 2})), AllOf(StartsWith("m.xml:5: "), HasSubstr("not finite")));
  EXPECT_THAT(InputErrorOf(make({0, 1}, {1, INFINITY})), HasSubstr("not finite"));
  // The spline is validated the same way.
  EXPECT_THROW(PointsLaw({1, 1}, {0, 0}, Interp::kSpline, Extrap::kLinear, 0.0, "m.xml:5"), InputError);
}

TEST(ForceLawTest, ExpressionGetsXVTimeAndInputsInOrder) {
  auto f = std::make_shared<Recorder>();
  const ExpressionLaw law(f, true);
  EXPECT_TRUE(law.depends_on_inputs());
  const std::vector<double> args = {0.25, 10.0, 20.0};  // [t, inputs...]
  ElementContext ctx;
  ctx.t = 0.25;
  ctx.parameter_args = args;
  const double value = law.Force(0.5, -2.0, ctx);
  EXPECT_EQ(f->last, (std::vector<double>{0.5, -2.0, 0.25, 10.0, 20.0}));
  EXPECT_NEAR(value, 0.5 - 4.0 + 0.75 + 40.0 + 100.0, 1e-12);
  // Without a mechanism's arguments the law still passes t.
  ElementContext bare;
  bare.t = 3.0;
  law.Force(1.0, 2.0, bare);
  EXPECT_EQ(f->last, (std::vector<double>{1.0, 2.0, 3.0}));
  EXPECT_FALSE(ExpressionLaw(f, false).depends_on_inputs());
}

TEST(ForceLawTest, ExpressionRefusesMoreInputsThanItsBufferHolds) {
  const ExpressionLaw law(std::make_shared<Recorder>(), false);
  std::vector<double> args(1 + ExpressionLaw::kMaxInputs, 1.0);
  ElementContext ctx;
  ctx.parameter_args = args;
  EXPECT_NO_THROW(law.Force(0.0, 0.0, ctx));
  args.push_back(1.0);
  ctx.parameter_args = args;
  EXPECT_THROW(law.Force(0.0, 0.0, ctx), SimulationError);
}

// ---------------------------------------------------------------------------
// Bipolar and joint forces: signs, sensors, F-2 through the dynamics

TEST(BipolarForceTest, RepulsionIsPositive) {
  // Spring between the ground point (0,0,2) and the box centre at z = 0.5:
  // compressed below its 2 m free length, so it pushes the box down.
  std::vector<double> sensors;
  EXPECT_NEAR(Acceleration(Slider(0.5),
                           One(std::make_unique<BipolarForce>("s", "", 0, Vec3(0, 0, 2), 1, Vec3::Zero(),
                                                              std::make_unique<LinearLaw>(100.0, 2.0, 0.0, 0.0))),
                           &sensors),
              -100.0 * 0.5 / 10.0, 1e-12);
  EXPECT_NEAR(sensors[0], 50.0, 1e-12);  // repulsion
  EXPECT_NEAR(sensors[1], 1.5, 1e-12);
  // The same spring below the box pushes it up.
  EXPECT_NEAR(Acceleration(Slider(0.5), One(std::make_unique<BipolarForce>(
                                            "s", "", 0, Vec3(0, 0, -1), 1, Vec3::Zero(),
                                            std::make_unique<LinearLaw>(100.0, 2.0, 0.0, 0.0)))),
              +100.0 * 0.5 / 10.0, 1e-12);
}

// A line along a coordinate axis is measured without a square root; the
// numbers are those of the general formula, bit for bit, on every axis and
// in both directions, and off the axes the general formula is used.
TEST(BipolarForceTest, LinesAlongAnAxisMeasureAsTheGeneralFormula) {
  for (int axis = 0; axis < 4; ++axis)  // 3: off the axes
    for (const double side : {1.0, -1.0}) {
      std::array<double, 6> q0{0.1, -0.2, 0.3, 0.0, 0.0, 0.0};  // the box origin, not turned
      const Vec3 anchor = Vec3(0.1, -0.2, 0.3) - side * (axis < 3 ? 0.7 * Vec3::Unit(axis) : Vec3(0.3, 0.4, 0.5));
      ModelBuilder m;
      m.SetGravity(Vec3::Zero());
      m.AddBody(testing::Box("Box", 1.0, {0.1, 0.1, 0.1}));
      m.AddJoint(Cardan("j", "Base0", "Box", q0));
      auto model = m.Build();
      Kinematics kin(*model);
      const std::vector<double> v{0.3, -1.1, 0.7, 0.0, 0.0, 0.0};  // translation only: the box point stays on the axis
      UpdateKinematics(*model, 0.0, model->initial_q(), v, &kin);
      const BipolarGeometry g = MeasureBipolar(kin, 0, anchor, 1, Vec3::Zero());
      const Vec3 d = PointPosition(kin, 1, Vec3::Zero()) - anchor;
      const double x = d.norm();
      const Vec3 u = d / x;
      const double rate = (PointVelocity(kin, 1, Vec3::Zero()) - PointVelocity(kin, 0, anchor)).dot(u);
      EXPECT_EQ(g.x, x) << axis << " " << side;
      EXPECT_EQ(g.u, u) << axis << " " << side;
      EXPECT_EQ(g.v, rate) << axis << " " << side;
      if (axis < 3) {
        EXPECT_EQ(g.u(axis), side);
      }
    }
}

// A point at its body's origin is measured without turning it: the same
// numbers as the general formula, on a turned and spinning body, at either end.
TEST(BipolarForceTest, PointsAtTheBodyOriginMeasureAsTheGeneralFormula) {
  ModelBuilder m;
  m.SetGravity(Vec3::Zero());
  m.AddBody(testing::Box("Box", 1.0, {0.1, 0.1, 0.1}));
  m.AddJoint(Cardan("j", "Base0", "Box", {0.1, -0.2, 0.3, 0.4, -0.5, 0.6}));
  auto model = m.Build();
  Kinematics kin(*model);
  const std::vector<double> v{0.3, -1.1, 0.7, 2.0, -3.0, 1.5};
  UpdateKinematics(*model, 0.0, model->initial_q(), v, &kin);
  const Vec3 anchor(0.9, 0.4, -0.3);
  for (const Vec3& on_box : {Vec3(Vec3::Zero()), Vec3(0.05, -0.02, 0.03)})
    for (const bool box_first : {false, true}) {
      const int b1 = box_first ? 1 : 0, b2 = box_first ? 0 : 1;
      const Vec3 p1 = box_first ? on_box : anchor, p2 = box_first ? anchor : on_box;
      const BipolarGeometry g = MeasureBipolar(kin, b1, p1, b2, p2);
      const Vec3 d = PointPosition(kin, b2, p2) - PointPosition(kin, b1, p1);
      const Vec3 u = d / d.norm();
      EXPECT_EQ(g.pa, PointPosition(kin, b1, p1));
      EXPECT_EQ(g.pb, PointPosition(kin, b2, p2));
      EXPECT_EQ(g.x, d.norm());
      EXPECT_EQ(g.u, u);
      EXPECT_EQ(g.v, (PointVelocity(kin, b2, p2) - PointVelocity(kin, b1, p1)).dot(u));
    }
}

// A Frictional element's crossing functions read the rate its Evaluate
// measured on the same kinematics, and measure it themselves on any other:
// the same numbers either way, never a stale rate.
TEST(FrictionalForceTest, CrossingsReuseTheRateOnlyOfTheSameKinematics) {
  ModelBuilder m;
  m.SetGravity(Vec3::Zero());
  m.AddBody(testing::Box("Box", 10.0, {0.1, 0.1, 0.1}));
  m.AddJoint(testing::ChainJoint("j", "Base0", "Box", {Et(T::kTv, Vec3::UnitX(), 0.5, 1.5)}));
  auto model = m.Build();
  FrictionalParameters p;
  p.friction = 10.0;
  p.stiffness = 1e5;
  p.damping = 100.0;
  std::vector<std::unique_ptr<ForceElement>> elements;
  elements.push_back(std::make_unique<FrictionalForce>("f", "", 0, Vec3(0.0, 0.0, 0.0), 1, Vec3(0.0, 0.0, 0.0), p));
  Mechanism mech(model, std::move(elements), {});
  MechanismWorkspace ws(mech);
  std::vector<double> x(mech.num_states()), modes(mech.num_modes());
  InitialState(mech, {}, x, modes, &ws);
  ASSERT_EQ(modes[0], 1.0);  // sliding apart: its first crossing is the rate
  const std::vector<int> all{0};
  auto crossings = [&] {
    std::vector<double> g(4);
    EvaluateCrossings(mech, x, modes, &ws, g);
    return g;
  };
  EvaluatePositions(mech, 0.0, x, &ws);
  EvaluateSensedElements(mech, 0.0, x, {}, modes, &ws, all);
  const std::vector<double> reused = crossings();
  EvaluateForCrossings(mech, 0.0, x, {}, &ws);  // new kinematics: measured again
  EXPECT_EQ(crossings(), reused);
  EXPECT_EQ(reused[0], 1.5);
  x[mech.model().nq()] = -0.25;  // another rate, the element not evaluated there
  EvaluateForCrossings(mech, 0.0, x, {}, &ws);
  EXPECT_EQ(crossings()[0], -0.25);
}

// A generalized force of 1 on coordinate 0 that throws while *fail is set.
class Flaky final : public ForceElement {
 public:
  explicit Flaky(const bool* fail) : ForceElement("flaky", "test"), fail_(fail) {}
  void Evaluate(const ElementContext&, Loads* loads, std::span<double>, std::span<double>) const override {
    loads->AddGeneralizedForce(0, 1.0);
    if (*fail_) throw SimulationError("flaky");
  }

 private:
  const bool* fail_;
};

// A sensors-only evaluation takes no loads; one that throws must not leave
// the loads discarding, or the next full evaluation would lose its forces.
TEST(LoadsTest, ASensorsOnlyEvaluationThatThrowsLeavesTheLoadsWhole) {
  bool fail = true;
  std::vector<std::unique_ptr<ForceElement>> elements;
  elements.push_back(std::make_unique<Flaky>(&fail));
  Mechanism mech(Slider(0.0), std::move(elements), {});
  MechanismWorkspace ws(mech);
  std::vector<double> x(mech.num_states()), xdot(mech.num_states());
  InitialState(mech, {}, x, {}, &ws);
  const std::vector<int> all{0};
  EvaluatePositions(mech, 0.0, x, &ws);
  EXPECT_THROW(EvaluateSensedElements(mech, 0.0, x, {}, {}, &ws, all), SimulationError);
  fail = false;
  EvaluateMechanism(mech, 0.0, x, {}, {}, &ws, xdot);
  EXPECT_DOUBLE_EQ(xdot[mech.model().nq()], 1.0 / 10.0);  // 1 N on the 10 kg box
}

TEST(BipolarForceTest, ObliqueLineProjectsOntoTheJoint) {
  // Ground point A = (0.3, 0, 0), box point B = its centre at z = 0.4:
  // x = 0.5, u = (-0.6, 0, 0.8); F = -100 (0.5 - 1) = 50 pushes the box along
  // u, the slider takes 50 * 0.8 = 40 N: a = 4 m/s^2.
  const BipolarForce spring("s", "", 0, Vec3(0.3, 0, 0), 1, Vec3::Zero(),
                            std::make_unique<LinearLaw>(100.0, 1.0, 0.0, 0.0));
  Probe probe(Slider(0.4));
  const auto sensors = probe.Run(spring);
  EXPECT_NEAR(sensors[0], 50.0, 1e-12);
  EXPECT_NEAR(sensors[1], 0.5, 1e-12);
  EXPECT_NEAR(probe.Generalized()[0], 40.0, 1e-12);
  EXPECT_NEAR(Acceleration(Slider(0.4), One(std::make_unique<BipolarForce>(
                                            "s", "", 0, Vec3(0.3, 0, 0), 1, Vec3::Zero(),
                                            std::make_unique<LinearLaw>(100.0, 1.0, 0.0, 0.0)))),
              4.0, 1e-12);
}

TEST(BipolarForceTest, RateIsTheLengthsRateAndTheDamperResists) {
  // Box at z = 0.5 moving up at 2 m/s. Anchor below: the length grows at 2;
  // anchor above: it shrinks at 2. A pure damper (d = 3) pulls (F = -6) when
  // the length grows, so in both cases it decelerates the box: a = -0.6.
  for (double anchor : {-1.0, 2.0}) {
    std::vector<double> sensors;
    const double a = Acceleration(Slider(0.5, 2.0),
                                  One(std::make_unique<BipolarForce>("d", "", 0, Vec3(0, 0, anchor), 1, Vec3::Zero(),
                                                                     std::make_unique<LinearLaw>(0.0, 0.0, 3.0, 0.0))),
                                  &sensors);
    const double rate = anchor < 0.5 ? 2.0 : -2.0;
    EXPECT_NEAR(sensors[2], rate, 1e-12) << anchor;
    EXPECT_NEAR(sensors[0], -3.0 * rate, 1e-12) << anchor;
    EXPECT_NEAR(a, -0.6, 1e-12) << anchor;
  }
}

TEST(BipolarForceTest, EqualAndOppositeOnTwoFreeBodies) {
  auto model = TwoFreeBodies();
  std::mt19937 rng(7);
  std::vector<double> q, v;
  testing::RandomState(*model, &rng, &q, &v);
  const Vec3 a_local(0.1, -0.2, 0.05), b_local(-0.1, 0.1, 0.2);
  const BipolarForce spring("s", "", 1, a_local, 2, b_local, std::make_unique<LinearLaw>(80.0, 3.0, 5.0, 1.0));
  Probe probe(model);
  const auto sensors = probe.Run(spring, q, v);
  const Vec3 pa = PointPosition(probe.kin, 1, a_local), pb = PointPosition(probe.kin, 2, b_local);
  const double x = (pb - pa).norm();
  const Vec3 u = (pb - pa) / x;
  const double rate = (PointVelocity(probe.kin, 2, b_local) - PointVelocity(probe.kin, 1, a_local)).dot(u);
  const double f = -80.0 * (x - 3.0) - 5.0 * rate + 1.0;
  EXPECT_NEAR(sensors[0], f, 1e-12 * 100);
  EXPECT_NEAR(sensors[1], x, 1e-12);
  EXPECT_NEAR(sensors[2], rate, 1e-12);
  // Collinear, equal and opposite: no resultant force or moment.
  const Vec6 resultant = probe.Resultant();
  EXPECT_LT(resultant.norm(), 1e-12 * std::abs(f) * 10);
  // Each centre of mass accelerates with its share: +F u / m_B and -F u / m_A.
  DynamicsWorkspace ws(*model);
  std::vector<double> vdot(model->nv());
  ForwardDynamics(*model, probe.kin, probe.loads.generalized(), probe.loads.segment_loads(), vdot, &ws);
  const Vec3 acc_a = PointAcceleration(*model, probe.kin, ws, 1, model->bodies()[1].com);
  const Vec3 acc_b = PointAcceleration(*model, probe.kin, ws, 2, model->bodies()[2].com);
  EXPECT_LT((acc_b - f * u / 3.0).norm(), 1e-10 * std::abs(f));
  EXPECT_LT((acc_a + f * u / 2.0).norm(), 1e-10 * std::abs(f));
}

TEST(BipolarForceTest, ZeroLengthAppliesNothingWhenTheForceVanishesElseFails) {
  // Box centre exactly at the ground point (0,0,0.3).
  Probe probe(Slider(0.3, 1.0));
  const BipolarForce zero("s", "", 0, Vec3(0, 0, 0.3), 1, Vec3::Zero(),
                          std::make_unique<LinearLaw>(100.0, 0.0, 5.0, 0.0));
  const auto sensors = probe.Run(zero);
  EXPECT_EQ(sensors[0], 0.0);
  EXPECT_EQ(sensors[1], 0.0);
  EXPECT_EQ(sensors[2], 0.0);  // no direction: the rate is taken as 0
  EXPECT_EQ(probe.Generalized()[0], 0.0);
  const BipolarForce preloaded("pre", "", 0, Vec3(0, 0, 0.3), 1, Vec3::Zero(),
                               std::make_unique<LinearLaw>(100.0, 0.0, 0.0, 2.0));
  try {
    probe.Run(preloaded);
    ADD_FAILURE() << "no SimulationError";
  } catch (const SimulationError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("'pre'"));
    EXPECT_THAT(e.what(), ::testing::HasSubstr("zero length"));
  }
}

TEST(JointForceTest, PositiveForceIncreasesTheCoordinate) {
  std::vector<double> sensors;
  auto slider = Slider(0.5, -0.25);
  EXPECT_NEAR(Acceleration(slider,
                           One(std::make_unique<JointForce>("f", "", slider->dofs()[0],
                                                            std::make_unique<LinearLaw>(0.0, 0.0, 0.0, 7.0))),
                           &sensors),
              0.7, 1e-12);
  EXPECT_NEAR(sensors[0], 7.0, 1e-12);
  EXPECT_NEAR(sensors[1], 0.5, 1e-12);    // length = the coordinate
  EXPECT_NEAR(sensors[2], -0.25, 1e-12);  // rate = its velocity
  // On a rotation it is a torque: alpha = T / I_zz, I_zz = 10 (0.2^2 + 0.2^2) / 12.
  auto turntable = Turntable(0.3);
  EXPECT_NEAR(Acceleration(turntable, One(std::make_unique<JointForce>(
                                          "t", "", turntable->dofs()[0],
                                          std::make_unique<LinearLaw>(2.0, 0.0, 0.0, 0.0)))),
              -2.0 * 0.3 / (10.0 * 0.08 / 12.0), 1e-12);
}

TEST(ForceElementsTest, F2TableAndLinearAccelerateAlikeAsBipolarAndJointForces) {
  // ELEMENTS F-2 and Forces (9.7): table {(-1,500),(0,0),(1,-500)} against
  // Linear c = 500, x0 = 0, for a 10 kg body: a = -500 z / 10.
  auto table = [] {
    return std::make_unique<PointsLaw>(std::vector<double>{-1, 0, 1}, std::vector<double>{500, 0, -500},
                                       Interp::kLinear, Extrap::kLinear, 0.0, "");
  };
  auto linear = [] { return std::make_unique<LinearLaw>(500.0, 0.0, 0.0, 0.0); };
  for (double z : {-2.5, -1.0, -0.3, 0.0, 0.2, 1.0, 3.0}) {
    const double expected = -500.0 * z / 10.0, tol = 1e-12 * 50 * (1 + std::abs(z));
    auto model = Slider(z);
    // Joint force on the slider coordinate.
    EXPECT_NEAR(Acceleration(model, One(std::make_unique<JointForce>("j", "", model->dofs()[0], table()))), expected,
                tol)
        << z;
    EXPECT_NEAR(Acceleration(model, One(std::make_unique<JointForce>("j", "", model->dofs()[0], linear()))),
                expected, tol)
        << z;
    // Bipolar between the ground origin and the box centre: x = |z|, and at
    // z = 0 the zero force of both laws applies nothing.
    EXPECT_NEAR(Acceleration(model, One(std::make_unique<BipolarForce>("b", "", 0, Vec3::Zero(), 1, Vec3::Zero(),
                                                                       table()))),
                expected, tol)
        << z;
    EXPECT_NEAR(Acceleration(model, One(std::make_unique<BipolarForce>("b", "", 0, Vec3::Zero(), 1, Vec3::Zero(),
                                                                       linear()))),
                expected, tol)
        << z;
  }
}

TEST(ForceElementsTest, ExpressionLawSeesTheMechanismsInputs) {
  // F = 1 * x + 2 * v + 3 * t + 4 * u (the Recorder's weights), at x = 0.5,
  // v = 0 (the slider starts at rest), t = 0.1, input u = 2.
  auto model = Slider(0.5);
  auto f = std::make_shared<Recorder>();
  std::vector<double> sensors;
  const double a = Acceleration(
      model, One(std::make_unique<JointForce>("e", "", model->dofs()[0], std::make_unique<ExpressionLaw>(f, true))),
      &sensors, {"u"}, {2.0}, 0.1);
  EXPECT_EQ(f->last, (std::vector<double>{0.5, 0.0, 0.1, 2.0}));
  EXPECT_NEAR(sensors[0], 0.5 + 0.3 + 8.0, 1e-12);
  EXPECT_NEAR(a, (0.5 + 0.3 + 8.0) / 10.0, 1e-12);
}

TEST(ForceElementsTest, ElementsDependOnInputsOnlyThroughTheirLaws) {
  auto model = Slider(0.0);
  const Parameter from_input = FunctionParameter(std::make_shared<ArgumentTimes>(1, 1.0), true);
  const Parameter from_time = FunctionParameter(std::make_shared<ArgumentTimes>(0, 1.0), false);
  EXPECT_TRUE(JointForce("a", "", model->dofs()[0], std::make_unique<LinearLaw>(0.0, 0.0, from_input, 0.0))
                  .depends_on_inputs());
  EXPECT_FALSE(JointForce("b", "", model->dofs()[0], std::make_unique<LinearLaw>(from_time, 0.0, 0.0, 0.0))
                   .depends_on_inputs());
  EXPECT_TRUE(BipolarForce("c", "", 0, Vec3::Zero(), 1, Vec3::Zero(),
                           std::make_unique<PointsLaw>(std::vector<double>{0, 1}, std::vector<double>{0, 1},
                                                       Interp::kLinear, Extrap::kLinear, from_input, ""))
                  .depends_on_inputs());
  EXPECT_FALSE(AppliedForce("d", "", 1, Vec3::Zero(), {from_time, 0.0, 0.0}, {}, false).depends_on_inputs());
  EXPECT_TRUE(AppliedForce("e", "", 1, Vec3::Zero(), {}, {0.0, 0.0, from_input}, false).depends_on_inputs());
}

// ---------------------------------------------------------------------------
// Bushing

BushingParameters FullBushing() {
  BushingParameters p;
  p.stiffness = {100.0, 200.0, 300.0};
  p.damping = {1.0, 2.0, 3.0};
  p.angular_stiffness = {10.0, 20.0, 30.0};
  p.angular_damping = {0.1, 0.2, 0.3};
  p.preload_force = Vec3(1.0, 2.0, 3.0);
  p.preload_moment = Vec3(0.5, 0.6, 0.7);
  return p;
}

TEST(BushingTest, HandNumbersAgainstTheGround) {
  // Body 1 = ground (P1 = (0,0,1)); body 2 on a Cardan chain, starting at
  // zero with P2 auto-detected at its local (0,0,1). Then moved by
  // (0.01,-0.02,0.03), turned 0.01 about z, with rates (vx,vy,vz) =
  // (0.1,0.2,-0.3) and omega = (0.4,-0.5,0.6) (global at zero x, y angles).
  const auto model = TwoCardanBodies({}, {});  // use body A only; B stays put
  Kinematics kin0(*model);
  UpdateKinematics(*model, 0.0, model->initial_q(), model->initial_v(), &kin0);
  const Vec3 p1(0, 0, 1);
  const Vec3 p2 = BushingCoincidentPoint(kin0, 0, p1, 1);
  EXPECT_LT((p2 - Vec3(0, 0, 1)).norm(), 1e-15);
  const Bushing bushing("b", "", 0, p1, 1, p2, FullBushing(), kin0);
  std::vector<double> q(model->nq(), 0.0), v(model->nv(), 0.0);
  const double qa[6] = {0.01, -0.02, 0.03, 0.0, 0.0, 0.01}, va[6] = {0.1, 0.2, -0.3, 0.4, -0.5, 0.6};
  for (int i = 0; i < 6; ++i) q[i] = qa[i], v[i] = va[i];
  Probe probe(model);
  const auto s = probe.Run(bushing, q, v);
  // Delta = translation (the rotation about z does not move a point on z);
  // Delta' = v + omega x (0,0,1); theta = (0, 0, sin 0.01).
  const Vec3 delta(0.01, -0.02, 0.03), delta_rate(0.1 - 0.5, 0.2 - 0.4, -0.3), theta(0, 0, std::sin(0.01));
  const Vec3 omega(0.4, -0.5, 0.6);
  const BushingParameters p = FullBushing();
  for (int i = 0; i < 3; ++i) {
    const double f = -(p.stiffness[i] * delta(i) + p.damping[i] * delta_rate(i)) + p.preload_force(i);
    const double m = -(p.angular_stiffness[i] * theta(i) + p.angular_damping[i] * omega(i)) + p.preload_moment(i);
    EXPECT_NEAR(s[i], f, 1e-12 * 10) << i;
    EXPECT_NEAR(s[3 + i], m, 1e-12 * 10) << i;
    EXPECT_NEAR(s[6 + i], delta(i), 1e-15) << i;
    EXPECT_NEAR(s[9 + i], theta(i), 1e-15) << i;
  }
  // The generalized forces on body 2's chain: the force, and the moment about
  // its origin of the force at P2 = (0.01,-0.02,1.03) plus the moment.
  const Vec3 f(s[0], s[1], s[2]), m(s[3], s[4], s[5]);
  const Vec3 moment = (Vec3(0.01, -0.02, 1.03) - Vec3(0.01, -0.02, 0.03)).cross(f) + m;
  const auto Q = probe.Generalized();
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(Q[i], f(i), 1e-12 * 10) << i;
    EXPECT_NEAR(Q[3 + i], moment(i), 1e-12 * 10) << i;
  }
  for (int i = 6; i < 12; ++i) EXPECT_EQ(Q[i], 0.0) << i;
}

TEST(BushingTest, WorksInTheAxesOfBody1) {
  // Body 1 (A) turned 90 degrees about z; only c_x. Body 2 (B) moved +0.01
  // along global y = A's x axis: f_x = -1 in A's axes, -1 N along global y on B.
  const auto model = TwoCardanBodies({0, 0, 0, 0, 0, M_PI / 2}, {});
  Kinematics kin0(*model);
  UpdateKinematics(*model, 0.0, model->initial_q(), model->initial_v(), &kin0);
  BushingParameters p;
  p.stiffness = {100.0, 0.0, 0.0};
  const Bushing bushing("b", "", 1, Vec3::Zero(), 2, BushingCoincidentPoint(kin0, 1, Vec3::Zero(), 2), p, kin0);
  std::vector<double> q = model->initial_q();
  q[7] = 0.01;
  Probe probe(model);
  const auto s = probe.Run(bushing, q, model->initial_v());
  EXPECT_NEAR(s[6], 0.01, 1e-15);
  EXPECT_NEAR(s[7], 0.0, 1e-15);
  EXPECT_NEAR(s[0], -1.0, 1e-12);
  const auto Q = probe.Generalized();
  EXPECT_NEAR(Q[6], 0.0, 1e-12);
  EXPECT_NEAR(Q[7], -1.0, 1e-12);
  EXPECT_NEAR(Q[1], +1.0, 1e-12);  // the reaction on body 1
}

TEST(BushingTest, RelativeToTheInitialRelativeRotation) {
  // Both bodies start turned differently: no load in that configuration
  // (no preload), whatever the stiffnesses.
  const auto model = TwoCardanBodies({0.1, 0.2, 0.3, 0.4, -0.3, 1.0}, {0.5, -0.2, 0.1, -0.2, 0.3, -0.6});
  Kinematics kin0(*model);
  UpdateKinematics(*model, 0.0, model->initial_q(), model->initial_v(), &kin0);
  BushingParameters p = FullBushing();
  p.preload_force.setZero();
  p.preload_moment.setZero();
  const Vec3 p1(0.2, 0.1, -0.3);
  const Bushing bushing("b", "", 1, p1, 2, BushingCoincidentPoint(kin0, 1, p1, 2), p, kin0);
  Probe probe(model);
  const auto s = probe.Run(bushing);
  for (int i = 0; i < 12; ++i) EXPECT_NEAR(s[i], 0.0, 1e-12) << i;  // 300 N/m times rounding
}

TEST(BushingTest, EqualAndOppositeWrenchesOnTwoFreeBodies) {
  // Random initial and current states, every coefficient and preload: the
  // two wrenches cancel about every point (checked about the origin), and
  // body 2 gets A1 f at p2 and A1 m.
  auto model = TwoFreeBodies();
  std::mt19937 rng(11);
  for (int trial = 0; trial < 5; ++trial) {
    std::vector<double> q0, v0, q, v;
    testing::RandomState(*model, &rng, &q0, &v0);
    testing::RandomState(*model, &rng, &q, &v);
    Kinematics kin0(*model);
    UpdateKinematics(*model, 0.0, q0, v0, &kin0);
    const Vec3 p1(0.1, 0.2, -0.1), p2 = BushingCoincidentPoint(kin0, 1, p1, 2);
    EXPECT_LT((PointPosition(kin0, 2, p2) - PointPosition(kin0, 1, p1)).norm(), 1e-14);
    const Bushing bushing("b", "", 1, p1, 2, p2, FullBushing(), kin0);
    Probe probe(model);
    const auto s = probe.Run(bushing, q, v);
    const double scale = Vec3(s[0], s[1], s[2]).norm() + Vec3(s[3], s[4], s[5]).norm();
    ASSERT_GT(scale, 1.0);
    EXPECT_LT(probe.Resultant().norm(), 1e-12 * scale * 10) << trial;
    const Mat3& A1 = probe.kin.body_pose[1].R;
    const Vec3 f = A1 * Vec3(s[0], s[1], s[2]), m = A1 * Vec3(s[3], s[4], s[5]);
    const int seg = model->bodies()[2].segment;
    const Pose& frame = probe.kin.pose[seg];
    const Vec6& w = probe.loads.segment_loads()[seg];
    const Vec3 f_on_2 = frame.R * w.tail<3>();
    const Vec3 m_on_2_about_p2 = frame.R * w.head<3>() + (frame.p - PointPosition(probe.kin, 2, p2)).cross(f_on_2);
    EXPECT_LT((f_on_2 - f).norm(), 1e-12 * scale * 10) << trial;
    EXPECT_LT((m_on_2_about_p2 - m).norm(), 1e-12 * scale * 10) << trial;
  }
}

TEST(BushingTest, StiffnessLoadsAreTheGradientOfItsEnergy) {
  // Unequal translational stiffnesses and an equal angular one: the loads on
  // both moving bodies are minus the gradient of
  //   V = (1/2) delta^T C delta + c_a (3 - trace R_rel) / 2
  // (the angular law m = -c_a vee(R - R^T)/2 derives from that V), checked
  // by central differences in the Cardan coordinates of both bodies.
  const std::array<double, 6> qa0 = {0.1, 0.2, 0.3, 0.4, -0.3, 1.0}, qb0 = {0.5, -0.2, 0.1, -0.2, 0.3, -0.6};
  const auto model = TwoCardanBodies(qa0, qb0);
  Kinematics kin(*model);
  UpdateKinematics(*model, 0.0, model->initial_q(), model->initial_v(), &kin);
  BushingParameters p;
  p.stiffness = {100.0, 700.0, 2500.0};
  p.angular_stiffness = {40.0, 40.0, 40.0};
  const Vec3 p1(0.2, 0.1, -0.3), p2 = BushingCoincidentPoint(kin, 1, p1, 2);
  const Mat3 relative0 = kin.body_pose[1].R.transpose() * kin.body_pose[2].R;
  const Bushing bushing("b", "", 1, p1, 2, p2, p, kin);
  auto energy = [&](const std::vector<double>& q) {
    UpdateKinematics(*model, 0.0, q, model->initial_v(), &kin);
    const Mat3& A1 = kin.body_pose[1].R;
    const Vec3 delta = A1.transpose() * (PointPosition(kin, 2, p2) - PointPosition(kin, 1, p1));
    const Mat3 R = A1.transpose() * kin.body_pose[2].R * relative0.transpose();
    return 0.5 * (100.0 * delta(0) * delta(0) + 700.0 * delta(1) * delta(1) + 2500.0 * delta(2) * delta(2)) +
           40.0 * (3.0 - R.trace()) / 2.0;
  };
  std::vector<double> q = model->initial_q();
  const double dq[12] = {0.03, -0.05, 0.02, 0.1, -0.2, 0.15, -0.04, 0.01, 0.06, 0.2, 0.1, -0.25};
  for (int i = 0; i < 12; ++i) q[i] += dq[i];
  Probe probe(model);
  const auto s = probe.Run(bushing, q, model->initial_v());
  const auto Q = probe.Generalized();
  // The configuration tells the two readings of ELEMENTS 4 apart: body 1's
  // force at P1 instead of p2 would change its moment by delta x f.
  const Vec3 delta_global = PointPosition(probe.kin, 2, p2) - PointPosition(probe.kin, 1, p1);
  ASSERT_GT(delta_global.cross(probe.kin.body_pose[1].R * Vec3(s[0], s[1], s[2])).norm(), 1.0);
  const double h = 1e-6;
  for (int i = 0; i < 12; ++i) {
    std::vector<double> plus = q, minus = q;
    plus[i] += h;
    minus[i] -= h;
    const double gradient = (energy(plus) - energy(minus)) / (2 * h);
    EXPECT_NEAR(Q[i], -gradient, 1e-6) << i;
  }
}

TEST(BushingTest, HoldsTheSagOfBU1) {
  // BU-1: 10 kg on a bushing with only c_z = 39478.4 N/m (10 Hz): the static
  // sag m g / c_z = 2.485 mm is an equilibrium, the bushing carrying m g.
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
  // The bushing is neutral with the body at z = 0; the body starts at the sag.
  Kinematics kin(*model);
  std::vector<double> q_neutral = model->initial_q();
  q_neutral[2] = 0.0;
  UpdateKinematics(*model, 0.0, q_neutral, model->initial_v(), &kin);
  BushingParameters p;
  p.stiffness = {0, 0, 39478.4};
  std::vector<double> sensors;
  std::vector<std::unique_ptr<ForceElement>> e;
  e.push_back(std::make_unique<Bushing>("b", "", 0, Vec3::Zero(), 1, BushingCoincidentPoint(kin, 0, Vec3::Zero(), 1),
                                        p, kin));
  Mechanism mech(model, std::move(e), {});
  MechanismWorkspace ws(mech);
  std::vector<double> x(mech.num_states()), xdot(mech.num_states());
  InitialState(mech, {}, x, {}, &ws);
  EvaluateMechanism(mech, 0.0, x, {}, {}, &ws, xdot);
  EXPECT_NEAR(sag, 2.485e-3, 1e-6);
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(xdot[model->nq() + i], 0.0, 1e-12) << i;
  EXPECT_NEAR(ws.sensors[2], 98.1, 1e-9);  // fz on body 2
  EXPECT_NEAR(ws.sensors[8], -sag, 1e-15);  // dz
  EXPECT_NEAR(std::sqrt(39478.4 / 10.0) / (2 * M_PI), 10.0, 1e-4);
}

// ---------------------------------------------------------------------------
// Applied force

TEST(AppliedForceTest, GlobalForceAtAPointAndTorque) {
  // Body B on a Cardan chain at (0.5,-0.2,0.1), turned 0.7 about z. Force
  // (3,-4,5) at its local point (0.2,0,0.1), torque (1,2,3), global axes:
  // generalized forces = the force and the moment about B's origin.
  const auto model = TwoCardanBodies({}, {0.5, -0.2, 0.1, 0.0, 0.0, 0.7});
  const AppliedForce applied("a", "", 2, Vec3(0.2, 0, 0.1), {3.0, -4.0, 5.0}, {1.0, 2.0, 3.0}, false);
  Probe probe(model);
  const auto s = probe.Run(applied);
  EXPECT_EQ(s, (std::vector<double>{3, -4, 5, 1, 2, 3}));
  const Vec3 force(3, -4, 5), r(0.2 * std::cos(0.7), 0.2 * std::sin(0.7), 0.1);
  const Vec3 moment = r.cross(force) + Vec3(1, 2, 3);
  const auto Q = probe.Generalized();
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(Q[6 + i], force(i), 1e-12) << i;
    EXPECT_NEAR(Q[9 + i], moment(i), 1e-12) << i;
  }
  for (int i = 0; i < 6; ++i) EXPECT_EQ(Q[i], 0.0) << i;
}

TEST(AppliedForceTest, BodyAxesTurnWithTheBody) {
  // Turned 90 degrees about z: body x is global y, body y is global -x.
  const auto model = TwoCardanBodies({}, {0.0, 0.0, 0.0, 0.0, 0.0, M_PI / 2});
  const AppliedForce applied("a", "", 2, Vec3(0.5, 0, 0), {0.0, 4.0, 0.0}, {1.0, 0.0, 0.0}, true);
  Probe probe(model);
  const auto s = probe.Run(applied);
  EXPECT_EQ(s, (std::vector<double>{0, 4, 0, 1, 0, 0}));  // as given, body axes
  // Force (-4,0,0) at (0,0.5,0): moment (0,0,2); torque (0,1,0).
  const auto Q = probe.Generalized();
  const double expected[6] = {-4, 0, 0, 0, 1, 2};
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(Q[6 + i], expected[i], 1e-12) << i;
}

TEST(AppliedForceTest, ComponentsFollowTheInputs) {
  // f_z = 2.5 * u on the 10 kg slider, u = 4: a = 1.
  auto model = Slider(0.0);
  std::vector<double> sensors;
  const double a = Acceleration(
      model,
      One(std::make_unique<AppliedForce>(
          "a", "", 1, Vec3::Zero(),
          std::array<Parameter, 3>{0.0, 0.0, FunctionParameter(std::make_shared<ArgumentTimes>(1, 2.5), true)},
          std::array<Parameter, 3>{}, false)),
      &sensors, {"u"}, {4.0});
  EXPECT_NEAR(a, 1.0, 1e-12);
  EXPECT_NEAR(sensors[2], 10.0, 1e-12);
}

}  // namespace
}  // namespace mechflow::mech
