// The mechanism as a block: simulated by CVODE with projection, against
// closed forms.
#include "blocks/library/mechanism_block.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <new>

#include <gtest/gtest.h>

#include "blocks/framework/diagram_builder.h"
#include "blocks/framework/evaluation.h"
#include "blocks/library/constant.h"
#include "blocks/library/gain.h"
#include "blocks/solver/simulator.h"
#include "mech/applied_force.h"
#include "mech/errors.h"
#include "mech/force_law.h"
#include "mech/joint_force.h"
#include "tests/mech/mech_test_util.h"

// ---------------------------------------------------------------------------
// Counting replacements of the global allocation functions (as in
// tests/blocks/solver/no_allocation_test.cc): only counted inside CountAllocations.

namespace {

std::atomic<bool> g_counting{false};
std::atomic<long> g_new_calls{0};

void* Allocate(std::size_t size) {
  if (g_counting.load(std::memory_order_relaxed)) g_new_calls.fetch_add(1, std::memory_order_relaxed);
  return std::malloc(size == 0 ? 1 : size);
}

void* AllocateAligned(std::size_t size, std::align_val_t alignment) {
  if (g_counting.load(std::memory_order_relaxed)) g_new_calls.fetch_add(1, std::memory_order_relaxed);
  const auto a = static_cast<std::size_t>(alignment);
  const std::size_t rounded = (size + a - 1) / a * a;
  return std::aligned_alloc(a, rounded == 0 ? a : rounded);
}

[[gnu::noinline]] void Deallocate(void* p) noexcept { std::free(p); }

}  // namespace

void* operator new(std::size_t size) {
  if (void* p = Allocate(size)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) {
  if (void* p = Allocate(size)) return p;
  throw std::bad_alloc();
}
void* operator new(std::size_t size, const std::nothrow_t&) noexcept { return Allocate(size); }
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept { return Allocate(size); }
void* operator new(std::size_t size, std::align_val_t alignment) {
  if (void* p = AllocateAligned(size, alignment)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size, std::align_val_t alignment) {
  if (void* p = AllocateAligned(size, alignment)) return p;
  throw std::bad_alloc();
}
void* operator new(std::size_t size, std::align_val_t alignment, const std::nothrow_t&) noexcept {
  return AllocateAligned(size, alignment);
}
void* operator new[](std::size_t size, std::align_val_t alignment, const std::nothrow_t&) noexcept {
  return AllocateAligned(size, alignment);
}
void operator delete(void* p) noexcept { Deallocate(p); }
void operator delete[](void* p) noexcept { Deallocate(p); }
void operator delete(void* p, std::size_t) noexcept { Deallocate(p); }
void operator delete[](void* p, std::size_t) noexcept { Deallocate(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { Deallocate(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { Deallocate(p); }
void operator delete(void* p, std::align_val_t) noexcept { Deallocate(p); }
void operator delete[](void* p, std::align_val_t) noexcept { Deallocate(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { Deallocate(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { Deallocate(p); }
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept { Deallocate(p); }
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept { Deallocate(p); }

// ---------------------------------------------------------------------------

namespace mechflow::blocks {
namespace {

// Counts operator new calls while alive. No GoogleTest macro may run inside
// (a failing assertion allocates its message).
class CountAllocations {
 public:
  CountAllocations() {
    g_new_calls = 0;
    g_counting = true;
  }
  ~CountAllocations() { g_counting = false; }
  long calls() const { return g_new_calls.load(); }
};

using mech::testing::Et;
using T = mech::TransformType;

mech::SensorSpec Sensor(const std::string& name, mech::SensorKind kind, int index, int component = -1) {
  mech::SensorSpec s;
  s.name = name;
  s.kind = kind;
  s.index = index;
  s.component = component;
  return s;
}

// k * input_0 (parameter arguments are [t, inputs...]).
class ScaledInput final : public mech::ScalarFunction {
 public:
  explicit ScaledInput(double k) : k_(k) {}
  double Evaluate(std::span<const double> args) const override { return k_ * args[1]; }

 private:
  double k_;
};

mech::Parameter InputParameter(double k) {
  mech::Parameter p;
  p.function = std::make_shared<ScaledInput>(k);
  p.uses_inputs = true;
  return p;
}

// Test-only element with memory: a bang-bang torque -T sign(q) on one DOF,
// the sign held as a mode and switched by the crossing of q through zero;
// one internal state integrates q. Sensors: torque, integral.
class BangBang final : public mech::ForceElement {
 public:
  BangBang(const mech::Dof& dof, double torque)
      : ForceElement("bang", "test"), q_(dof.q_index), v_(dof.v_index), torque_(torque) {
    DeclareSensor("torque");
    DeclareSensor("integral");
    DeclareStates(1);
    DeclareModes(1);
    DeclareCrossing(mech::Crossing::kEither);
  }
  void Initialize(const mech::ElementContext& ctx, std::span<double> state, std::span<double> modes) const override {
    state[0] = 0.0;
    modes[0] = ctx.q[q_] >= 0.0 ? 1.0 : -1.0;
  }
  void Evaluate(const mech::ElementContext& ctx, mech::Loads* loads, std::span<double> rate,
                std::span<double> sensors) const override {
    const double m = -torque_ * ctx.modes[0];
    loads->AddGeneralizedForce(v_, m);
    rate[0] = ctx.q[q_];
    sensors[0] = m;
    sensors[1] = ctx.state[0];
  }
  void ZeroCrossings(const mech::ElementContext& ctx, std::span<double> values) const override {
    values[0] = ctx.q[q_];
  }
  void OnCrossing(int, int direction, const mech::ElementContext&, std::span<double>,
                  std::span<double> modes) const override {
    modes[0] = direction > 0 ? 1.0 : -1.0;
  }

 private:
  int q_, v_;
  double torque_;
};

// Uniform thin rod of `mass` and `length` along -z of its body frame.
mech::BodySpec Rod(const std::string& name, double mass, double length) {
  mech::BodySpec rod = mech::testing::Box(name, mass, {0.005, 0.005, 0.5 * length}, mech::Vec3(0, 0, -0.5 * length));
  rod.inertia = mech::Vec3(mass * length * length / 12, mass * length * length / 12, 1e-6).asDiagonal();
  return rod;
}

std::shared_ptr<const mech::Mechanism> Make(mech::ModelBuilder* m,
                                            std::vector<std::unique_ptr<mech::ForceElement>> elements = {},
                                            std::vector<std::string> inputs = {}) {
  return std::make_shared<mech::Mechanism>(m->Build(), std::move(elements), std::move(inputs));
}

std::shared_ptr<const mech::Mechanism> Pendulum(double angle0) {
  // Uniform rod 1 kg, 1 m, hinged at its end about x, hanging along -z.
  mech::ModelBuilder m;
  mech::BodySpec rod = mech::testing::Box("Rod", 1.0, {0.005, 0.005, 0.5}, mech::Vec3(0, 0, -0.5));
  rod.inertia = mech::Vec3(1.0 / 12, 1.0 / 12, 1e-6).asDiagonal();
  m.AddBody(rod);
  m.AddJoint(mech::testing::ChainJoint("hinge", "Base0", "Rod", {Et(T::kRv, mech::Vec3::UnitX(), angle0)}));
  return std::make_shared<mech::Mechanism>(m.Build(), std::vector<std::unique_ptr<mech::ForceElement>>{},
                                           std::vector<std::string>{});
}

TEST(MechanismBlockTest, PendulumSmallAmplitudePeriod) {
  DiagramBuilder builder;
  builder.AddBlock(std::make_unique<MechanismBlock>(
      "p", Pendulum(0.01), std::vector<mech::SensorSpec>{Sensor("phi", mech::SensorKind::kCoordinate, 0)}));
  auto diagram = builder.Build();
  SolverOptions options;
  options.t_end = 10.0;
  options.rtol = 1e-10;
  options.atol = 1e-12;
  options.output_interval = 1e-3;
  Simulator sim(*diagram, options, {diagram->ResolveSignal("p.phi")});
  ASSERT_TRUE(sim.Run().ok);
  // Period from the downward zero crossings of phi.
  const Results& r = sim.results();
  std::vector<double> crossings;
  for (int i = 1; i < r.num_rows(); ++i)
    if (r.at(i - 1, 1) > 0 && r.at(i, 1) <= 0)
      crossings.push_back(r.at(i - 1, 0) + (r.at(i, 0) - r.at(i - 1, 0)) * r.at(i - 1, 1) / (r.at(i - 1, 1) - r.at(i, 1)));
  ASSERT_GE(crossings.size(), 3u);
  const double period = (crossings.back() - crossings.front()) / (crossings.size() - 1);
  const double expected = 2 * M_PI * std::sqrt((1.0 / 3.0) / (9.81 * 0.5));  // I_O / (m g l_c)
  EXPECT_NEAR(period / expected, 1.0, 1e-4);
  std::cout.precision(10);
  std::cout << "pendulum: period / 2 pi sqrt(I_O / (m g l_c)) = " << period / expected << "\n";
}

TEST(MechanismBlockTest, HangingPendulumReactionCarriesTheWeight) {
  DiagramBuilder builder;
  builder.AddBlock(std::make_unique<MechanismBlock>(
      "p", Pendulum(0.0),
      std::vector<mech::SensorSpec>{Sensor("r", mech::SensorKind::kReactionForce, 0),
                                    Sensor("a", mech::SensorKind::kAcceleration, 0)}));
  auto diagram = builder.Build();
  SolverOptions options;
  options.t_end = 0.1;
  Simulator sim(*diagram, options, {diagram->ResolveSignal("p.r"), diagram->ResolveSignal("p.a")});
  ASSERT_TRUE(sim.Run().ok);
  const Results& r = sim.results();
  EXPECT_NEAR(r.at(r.num_rows() - 1, 1), 0.0, 1e-12);
  EXPECT_NEAR(r.at(r.num_rows() - 1, 2), 0.0, 1e-12);
  EXPECT_NEAR(r.at(r.num_rows() - 1, 3), 9.81, 1e-12);  // upward force on the rod
  EXPECT_NEAR(r.at(r.num_rows() - 1, 4), 0.0, 1e-12);
}

TEST(MechanismBlockTest, FourBarStaysClosedWithProjection) {
  // Projection keeps a closed loop closed: 10 s with the position residual below 1e-8 at rtol 1e-8.
  mech::ModelBuilder m;
  auto rod = [](const std::string& name, double length) {
    return mech::testing::Box(name, length, {0.01, 0.5 * length, 0.01}, mech::Vec3(0, 0.5 * length, 0));
  };
  m.AddBody(rod("Crank", 0.3));
  m.AddBody(rod("Coupler", 0.8));
  m.AddBody(rod("Rocker", 0.6));
  m.AddJoint(mech::testing::ChainJoint("j1", "Base0", "Crank", {Et(T::kRv, mech::Vec3::UnitX(), 1.2, 6.0)}));
  m.AddJoint(mech::testing::ChainJoint("j2", "Crank", "Coupler",
                                       {Et(T::kTc, mech::Vec3::UnitY(), 0.3), Et(T::kRv, mech::Vec3::UnitX(), -1.0)}));
  m.AddJoint(mech::testing::ChainJoint("j3", "Base0", "Rocker",
                                       {Et(T::kTc, mech::Vec3::UnitY(), 0.7), Et(T::kRv, mech::Vec3::UnitX(), 1.9)}));
  mech::JointSpec close = mech::testing::ChainJoint(
      "j4", "Coupler", "Rocker", {Et(T::kTc, mech::Vec3::UnitY(), 0.8), Et(T::kRv, mech::Vec3::UnitX())});
  close.frame2 = mech::Pose::Translation(mech::Vec3(0, 0.6, 0));
  m.AddJoint(close);
  auto mechanism = std::make_shared<mech::Mechanism>(m.Build(), std::vector<std::unique_ptr<mech::ForceElement>>{},
                                                     std::vector<std::string>{});
  DiagramBuilder builder;
  auto block = std::make_unique<MechanismBlock>(
      "fb", mechanism, std::vector<mech::SensorSpec>{Sensor("crank", mech::SensorKind::kCoordinate, 0)});
  const MechanismBlock* fb = block.get();
  builder.AddBlock(std::move(block));
  auto diagram = builder.Build();
  SolverOptions options;
  options.t_end = 10.0;
  options.rtol = 1e-8;
  options.atol = 1e-10;
  Simulator sim(*diagram, options, {diagram->ResolveSignal("fb.crank")});
  const RunOutcome outcome = sim.Run();
  ASSERT_TRUE(outcome.ok) << outcome.failure;
  const double worst = fb->worst_constraint_residual(sim.context(), 0);
  EXPECT_LT(worst, 1e-8);
  EXPECT_GT(worst, 0.0) << "projection never ran";
  std::cout << "four-bar: worst residual before projection " << worst << ", steps "
            << sim.stats().steps << "\n";
}

mech::SensorSpec PointSensor(const std::string& name, mech::SensorKind kind, int body, const mech::Vec3& point,
                             int component = -1) {
  mech::SensorSpec s = Sensor(name, kind, body, component);
  s.point = point;
  return s;
}

mech::SensorSpec ElementSensor(const std::string& name, int element, int element_sensor) {
  mech::SensorSpec s = Sensor(name, mech::SensorKind::kElement, element);
  s.element_sensor = element_sensor;
  return s;
}

TEST(MechanismBlockTest, DoublePendulumConservesEnergy) {
  // Two uniform rods, 1 kg and 1 m each, hinged end to end about x.
  mech::ModelBuilder m;
  m.AddBody(Rod("Upper", 1.0, 1.0));
  m.AddBody(Rod("Lower", 1.0, 1.0));
  m.AddJoint(mech::testing::ChainJoint("j1", "Base0", "Upper", {Et(T::kRv, mech::Vec3::UnitX(), 1.2, 1.0)}));
  m.AddJoint(mech::testing::ChainJoint(
      "j2", "Upper", "Lower", {Et(T::kTc, mech::Vec3(0, 0, -1), 1.0), Et(T::kRv, mech::Vec3::UnitX(), -0.7)}));
  const mech::Vec3 com(0, 0, -0.5);
  std::vector<mech::SensorSpec> sensors;
  for (int b : {1, 2}) {
    const std::string n = std::to_string(b);
    sensors.push_back(PointSensor("p" + n, mech::SensorKind::kPointPosition, b, com));
    sensors.push_back(PointSensor("v" + n, mech::SensorKind::kPointVelocity, b, com));
    sensors.push_back(Sensor("w" + n, mech::SensorKind::kBodyAngularVelocity, b));
  }
  DiagramBuilder builder;
  builder.AddBlock(std::make_unique<MechanismBlock>("dp", Make(&m), sensors));
  auto diagram = builder.Build();
  SolverOptions options;
  options.t_end = 5.0;
  options.rtol = 1e-10;
  options.atol = 1e-12;
  options.output_interval = 1e-3;
  std::vector<SignalRef> logged;
  for (const auto& s : sensors) logged.push_back(diagram->ResolveSignal("dp." + s.name));
  Simulator sim(*diagram, options, logged);
  const RunOutcome outcome = sim.Run();
  ASSERT_TRUE(outcome.ok) << outcome.failure;
  const Results& r = sim.results();
  auto energy = [&](int row) {
    double e = 0.0;
    for (int b = 0; b < 2; ++b) {
      const int c = 1 + 9 * b;  // p, v, w of body b
      const double z = r.at(row, c + 2);
      const double v2 = std::pow(r.at(row, c + 3), 2) + std::pow(r.at(row, c + 4), 2) + std::pow(r.at(row, c + 5), 2);
      const double wx = r.at(row, c + 6), wy = r.at(row, c + 7), wz = r.at(row, c + 8);
      e += 0.5 * 1.0 * v2 + 0.5 * (1.0 / 12) * (wx * wx + wy * wy) + 0.5 * 1e-6 * wz * wz + 1.0 * 9.81 * z;
    }
    return e;
  };
  const double e0 = energy(0);
  double drift = 0.0;
  for (int i = 0; i < r.num_rows(); ++i) drift = std::max(drift, std::abs(energy(i) - e0));
  EXPECT_LT(drift / std::abs(e0), 1e-7) << "E0 = " << e0;
  // the motion is not a small one: the lower rod swings through large angles
  double max_w2 = 0.0;
  for (int i = 0; i < r.num_rows(); ++i) max_w2 = std::max(max_w2, std::abs(r.at(i, 16)));
  EXPECT_GT(max_w2, 2.0);
  std::cout << "double pendulum: E0 = " << e0 << " J, max relative energy drift over 5 s " << drift / std::abs(e0)
            << ", steps " << sim.stats().steps << "\n";
}

// A block of 2 kg on a slide inclined 30 deg from horizontal; an applied force
// along the slide is the mechanism's input F, driven by a constant block.
std::shared_ptr<const mech::Mechanism> InclinedSlider(double mass) {
  const double c = std::cos(M_PI / 6), s = std::sin(M_PI / 6);
  mech::ModelBuilder m;
  m.AddBody(mech::testing::Box("Block", mass, {0.1, 0.1, 0.1}));
  m.AddJoint(mech::testing::ChainJoint("slide", "Base0", "Block", {Et(T::kTv, mech::Vec3(0, c, s))}));
  auto model = m.Build();
  std::vector<std::unique_ptr<mech::ForceElement>> elements;
  elements.push_back(std::make_unique<mech::AppliedForce>(
      "push", "test", 1, mech::Vec3::Zero(),
      std::array<mech::Parameter, 3>{mech::Parameter(0.0), InputParameter(c), InputParameter(s)},
      std::array<mech::Parameter, 3>{}, false));
  elements.push_back(std::make_unique<mech::JointForce>(
      "spring", "test", model->dofs()[0], std::make_unique<mech::LinearLaw>(0.0, 0.0, 0.0, 0.0)));
  return std::make_shared<mech::Mechanism>(model, std::move(elements), std::vector<std::string>{"F"});
}

TEST(MechanismBlockTest, AppliedForceFromAnInputAcceleratesTheSlider) {
  const double mass = 2.0, force = 3.0;
  DiagramBuilder builder;
  builder.AddBlock(std::make_unique<ConstantBlock>("c", std::vector<double>{force}));
  builder.AddBlock(std::make_unique<MechanismBlock>(
      "slider", InclinedSlider(mass),
      std::vector<mech::SensorSpec>{Sensor("a", mech::SensorKind::kAcceleration, 0),
                                    PointSensor("pa", mech::SensorKind::kPointAcceleration, 1, mech::Vec3::Zero()),
                                    Sensor("x", mech::SensorKind::kCoordinate, 0),
                                    ElementSensor("fz", 0, 2)}));
  builder.Connect("c", "slider.F");
  auto diagram = builder.Build();
  SolverOptions options;
  options.t_end = 1.0;
  options.rtol = 1e-10;
  options.atol = 1e-12;
  Simulator sim(*diagram, options,
                {diagram->ResolveSignal("slider.a"), diagram->ResolveSignal("slider.pa"),
                 diagram->ResolveSignal("slider.x"), diagram->ResolveSignal("slider.fz")});
  const RunOutcome outcome = sim.Run();
  ASSERT_TRUE(outcome.ok) << outcome.failure;
  const double a = force / mass - 9.81 * std::sin(M_PI / 6);  // F/m + the gravity component along the slide
  const Results& r = sim.results();
  const int last = r.num_rows() - 1;
  for (int row : {0, last}) {
    EXPECT_NEAR(r.at(row, 1), a, 1e-12);
    EXPECT_NEAR(r.at(row, 2), 0.0, 1e-12);
    EXPECT_NEAR(r.at(row, 3), a * std::cos(M_PI / 6), 1e-12);
    EXPECT_NEAR(r.at(row, 4), a * std::sin(M_PI / 6), 1e-12);
    EXPECT_NEAR(r.at(row, 6), force * std::sin(M_PI / 6), 1e-15);
  }
  EXPECT_NEAR(r.at(last, 5), 0.5 * a * 1.0, 1e-9);  // x(1 s) = a t^2 / 2
}

TEST(MechanismBlockTest, FeedthroughIsDeclaredPerSensor) {
  using K = mech::SensorKind;
  const std::vector<std::pair<mech::SensorSpec, bool>> expected = {
      {Sensor("q", K::kCoordinate, 0), false},
      {Sensor("v", K::kVelocity, 0), false},
      {Sensor("a", K::kAcceleration, 0), true},
      {Sensor("rf", K::kReactionForce, 0), true},
      {Sensor("rt", K::kReactionTorque, 0, 2), true},
      {ElementSensor("fz", 0, 2), true},  // this element's force follows the input
      {PointSensor("p", K::kPointPosition, 1, mech::Vec3(0.1, 0, 0)), false},
      {PointSensor("pv", K::kPointVelocity, 1, mech::Vec3(0.1, 0, 0)), false},
      {PointSensor("pa", K::kPointAcceleration, 1, mech::Vec3(0.1, 0, 0)), true},
      {Sensor("angles", K::kBodyAngles, 1), false},
      {Sensor("w", K::kBodyAngularVelocity, 1, 0), false}};
  std::vector<mech::SensorSpec> sensors;
  for (const auto& [s, _] : expected) sensors.push_back(s);
  const MechanismBlock block("slider", InclinedSlider(2.0), sensors);
  ASSERT_EQ(block.num_inputs(), 1);
  EXPECT_EQ(block.input_port(0).name, "F");
  ASSERT_EQ(block.num_outputs(), static_cast<int>(expected.size()));
  for (int out = 0; out < block.num_outputs(); ++out) {
    EXPECT_EQ(block.output_port(out).name, expected[out].first.name);
    EXPECT_EQ(block.output_port(out).width, mech::SensorWidth(expected[out].first));
    EXPECT_EQ(block.HasFeedthrough(0, out), expected[out].second) << expected[out].first.name;
  }
  EXPECT_EQ(block.output_port(3).width, 3);
  EXPECT_EQ(block.output_port(4).width, 1);

  // Position feedback into the force input is no algebraic loop (a spring
  // made of a gain: F = -100 x) ...
  {
    DiagramBuilder builder;
    builder.AddBlock(std::make_unique<MechanismBlock>("slider", InclinedSlider(2.0), sensors));
    builder.AddBlock(std::make_unique<GainBlock>("k", -100.0, 1));
    builder.Connect("slider.q", "k");
    builder.Connect("k", "slider.F");
    auto diagram = builder.Build();
    SolverOptions options;
    options.t_end = 2.0;
    Simulator sim(*diagram, options, {diagram->ResolveSignal("slider.q")});
    ASSERT_TRUE(sim.Run().ok);
    double lowest = 0.0;
    for (int i = 0; i < sim.results().num_rows(); ++i) lowest = std::min(lowest, sim.results().at(i, 1));
    EXPECT_NEAR(lowest, -2 * 2.0 * 9.81 * 0.5 / 100.0, 1e-5);  // static sag m g sin30 / k, twice at the bottom
  }
  // ... acceleration feedback is one, solved at every evaluation: F = -1 kg a
  // adds a kilogram, a = -m g sin30 / (m + 1).
  {
    DiagramBuilder builder;
    builder.AddBlock(std::make_unique<MechanismBlock>("slider", InclinedSlider(2.0), sensors));
    builder.AddBlock(std::make_unique<GainBlock>("k", -1.0, 1));
    builder.Connect("slider.a", "k");
    builder.Connect("k", "slider.F");
    auto diagram = builder.Build();
    ASSERT_EQ(diagram->loops().size(), 1u);
    SolverOptions options;
    options.t_end = 0.5;
    Simulator sim(*diagram, options, {diagram->ResolveSignal("slider.a")});
    ASSERT_TRUE(sim.Run().ok);
    for (int i = 0; i < sim.results().num_rows(); ++i)
      EXPECT_NEAR(sim.results().at(i, 1), -2.0 * 9.81 * 0.5 / 3.0, 1e-9);
  }
}

TEST(MechanismBlockTest, StatesModesAndCrossingsAreTheMechanisms) {
  mech::ModelBuilder m;
  m.AddBody(Rod("Rod", 1.0, 1.0));
  m.AddBody(mech::testing::Box("Ball", 0.5, {0.1, 0.1, 0.1}));
  m.AddJoint(mech::testing::ChainJoint("hinge", "Base0", "Rod", {Et(T::kRv, mech::Vec3::UnitX(), 0.3)}));
  mech::JointSpec free;
  free.name = "float";
  free.body1 = "Base0";
  free.body2 = "Ball";
  free.quaternion = true;
  m.AddJoint(free);
  auto model = m.Build();
  std::vector<std::unique_ptr<mech::ForceElement>> elements;
  elements.push_back(std::make_unique<BangBang>(model->dofs()[0], 1.0));
  auto mechanism = std::make_shared<mech::Mechanism>(model, std::move(elements), std::vector<std::string>{});
  const MechanismBlock block("m", mechanism, {Sensor("q", mech::SensorKind::kCoordinate, 0)});
  std::vector<std::string> names;
  for (int i = 0; i < block.num_states(); ++i) names.push_back(block.state_name(i));
  EXPECT_EQ(names, (std::vector<std::string>{"q:hinge", "float.x", "float.y", "float.z", "float.qw", "float.qx",
                                             "float.qy", "float.qz", "v:hinge", "float.wx", "float.wy", "float.wz",
                                             "float.vx", "float.vy", "float.vz", "bang.s0"}));
  EXPECT_EQ(block.num_discrete_states(), 1);
  ASSERT_EQ(block.num_zero_crossings(), 1);
  EXPECT_EQ(block.crossing_direction(0), CrossingDirection::kEither);
  EXPECT_TRUE(block.has_projection());  // the quaternion
  // Nothing to project in a plain tree.
  EXPECT_FALSE(MechanismBlock("p", Pendulum(0.0), {}).has_projection());
}

// Test-only element without sensors that counts its evaluations (and loads nothing).
class Counted final : public mech::ForceElement {
 public:
  explicit Counted(long* calls) : ForceElement("counted", "test"), calls_(calls) {}
  void Evaluate(const mech::ElementContext&, mech::Loads*, std::span<double>, std::span<double>) const override {
    ++*calls_;
  }

 private:
  long* calls_;
};

// A rod hinged about x at q0, gravity off, under BangBang(torque); with
// `counted`, a Counted element comes first. Signals m.q, m.torque, m.integral.
std::unique_ptr<Diagram> BangBangRod(double q0, double torque, long* counted = nullptr) {
  mech::ModelBuilder m;
  m.SetGravity(mech::Vec3::Zero());
  m.AddBody(Rod("Rod", 1.0, 1.0));
  m.AddJoint(mech::testing::ChainJoint("hinge", "Base0", "Rod", {Et(T::kRv, mech::Vec3::UnitX(), q0)}));
  auto model = m.Build();
  std::vector<std::unique_ptr<mech::ForceElement>> elements;
  if (counted) elements.push_back(std::make_unique<Counted>(counted));
  const int bang = static_cast<int>(elements.size());
  elements.push_back(std::make_unique<BangBang>(model->dofs()[0], torque));
  auto mechanism = std::make_shared<mech::Mechanism>(model, std::move(elements), std::vector<std::string>{});
  DiagramBuilder builder;
  builder.AddBlock(std::make_unique<MechanismBlock>(
      "m", mechanism,
      std::vector<mech::SensorSpec>{Sensor("q", mech::SensorKind::kCoordinate, 0), ElementSensor("torque", bang, 0),
                                    ElementSensor("integral", bang, 1)}));
  return builder.Build();
}

TEST(MechanismBlockTest, ElementCrossingsSwitchModes) {
  // Without gravity, a rod released at q0 under the torque -T sign(q) moves
  // along parabolas: it reaches q = 0 after t1 = sqrt(2 q0 I_O / T) and is
  // back at q0 after 4 t1, where the integral of q over the period is zero.
  const double q0 = 0.3, torque = 1.0, inertia = 1.0 / 3.0;
  const double t1 = std::sqrt(2 * q0 * inertia / torque);
  auto diagram = BangBangRod(q0, torque);
  SolverOptions options;
  options.t_end = 4 * t1;
  options.rtol = 1e-10;
  options.atol = 1e-12;
  Simulator sim(*diagram, options,
                {diagram->ResolveSignal("m.q"), diagram->ResolveSignal("m.torque"), diagram->ResolveSignal("m.integral")});
  const RunOutcome outcome = sim.Run();
  ASSERT_TRUE(outcome.ok) << outcome.failure;
  ASSERT_EQ(sim.events().size(), 2u);
  EXPECT_NEAR(sim.events()[0].time, t1, 1e-8);
  EXPECT_EQ(sim.events()[0].direction, -1);
  EXPECT_NEAR(sim.events()[1].time, 3 * t1, 1e-8);
  EXPECT_EQ(sim.events()[1].direction, +1);
  const Results& r = sim.results();
  const int last = r.num_rows() - 1;
  EXPECT_NEAR(r.at(last, 1), q0, 1e-8);
  EXPECT_EQ(r.at(last, 2), -torque);
  EXPECT_NEAR(r.at(last, 3), 0.0, 1e-8);
  EXPECT_EQ(r.at(0, 2), -torque);
}

// An output row reads element sensors from the elements that have them:
// an element nobody senses is evaluated for the right-hand sides only.
TEST(MechanismBlockTest, RowsEvaluateOnlyTheSensedElements) {
  const double torque = 1.0;
  long counted_calls = 0;
  auto diagram = BangBangRod(0.3, torque, &counted_calls);
  SolverOptions options;
  options.t_end = 1.0;
  options.output_interval = 1e-4;  // far more rows than right-hand sides (the motion is parabolic)
  Simulator sim(*diagram, options,
                {diagram->ResolveSignal("m.q"), diagram->ResolveSignal("m.torque"), diagram->ResolveSignal("m.integral")});
  const RunOutcome outcome = sim.Run();
  ASSERT_TRUE(outcome.ok) << outcome.failure;
  const Results& r = sim.results();
  ASSERT_EQ(r.num_rows(), 10001);
  const long evaluations = sim.stats().rhs_evals + sim.stats().jac_rhs_evals;
  EXPECT_LT(evaluations, 2000);
  EXPECT_GE(counted_calls, evaluations);
  EXPECT_LE(counted_calls, evaluations + 20) << "rows evaluate the unsensed element";
  // the sensed element's values are its own: the torque opposes q, the
  // integral of q grows while q > 0 (the rod reaches q = 0 at t = 0.77 s)
  for (int i = 0; i < r.num_rows(); i += 500) {
    EXPECT_EQ(r.at(i, 2), r.at(i, 1) >= 0.0 ? -torque : torque) << r.at(i, 0);
    if (i > 0 && r.at(i, 1) > 0.0) {
      EXPECT_GT(r.at(i, 3), r.at(i - 500, 3)) << r.at(i, 0);
    }
  }
}

// Counts its evaluations: one per evaluation of the kinematics.
class CountedMotion final : public mech::TimeFunction {
 public:
  CountedMotion(double speed, long* calls) : speed_(speed), calls_(calls) {}
  mech::Jet Evaluate(double t) const override {
    ++*calls_;
    return {speed_ * t, speed_, 0.0};
  }

 private:
  double speed_;
  long* calls_;
};

// A root check at an output time and the row there share one evaluation: the
// kinematics are computed once for both, whichever port (a position sensor
// or an element sensor) asks first.
TEST(MechanismBlockTest, ARowSharesTheKinematicsOfTheRootCheckAtItsTime) {
  long motions = 0;
  mech::ModelBuilder m;
  m.SetGravity(mech::Vec3::Zero());
  m.AddBody(mech::testing::Box("Cart", 1.0, {0.1, 0.1, 0.1}));
  m.AddBody(Rod("Rod", 1.0, 1.0));
  mech::TransformSpec slide = Et(T::kTt, mech::Vec3::UnitY());
  slide.function = std::make_shared<CountedMotion>(0.1, &motions);
  m.AddJoint(mech::testing::ChainJoint("slide", "Base0", "Cart", {slide}));
  m.AddJoint(mech::testing::ChainJoint("hinge", "Cart", "Rod", {Et(T::kRv, mech::Vec3::UnitX(), 0.3)}));
  auto model = m.Build();
  std::vector<std::unique_ptr<mech::ForceElement>> elements;
  elements.push_back(std::make_unique<BangBang>(model->dofs()[0], 1.0));
  auto mechanism = std::make_shared<mech::Mechanism>(model, std::move(elements), std::vector<std::string>{});
  // a position port on either side of the element ports: one of them comes
  // first in any schedule
  DiagramBuilder builder;
  builder.AddBlock(std::make_unique<MechanismBlock>(
      "m", mechanism,
      std::vector<mech::SensorSpec>{PointSensor("cart_first", mech::SensorKind::kPointPosition, 1, mech::Vec3::Zero(), 1),
                                    ElementSensor("torque", 0, 0), ElementSensor("integral", 0, 1),
                                    PointSensor("cart_last", mech::SensorKind::kPointPosition, 1, mech::Vec3::Zero(), 1)}));
  auto diagram = builder.Build();
  SolverOptions options;
  options.t_end = 1.0;
  options.output_interval = 1e-4;
  Simulator sim(*diagram, options,
                {diagram->ResolveSignal("m.cart_first"), diagram->ResolveSignal("m.torque"),
                 diagram->ResolveSignal("m.integral"), diagram->ResolveSignal("m.cart_last")});
  const RunOutcome outcome = sim.Run();
  ASSERT_TRUE(outcome.ok) << outcome.failure;
  const Results& r = sim.results();
  ASSERT_EQ(r.num_rows(), 10001);
  const SolverStats& s = sim.stats();
  ASSERT_GE(s.root_evals, 10001);  // CVODE checks the roots at every output time
  // each right-hand side and root check evaluates the kinematics once, and
  // the rows add none (else 10001 more)
  EXPECT_LE(motions, s.rhs_evals + s.jac_rhs_evals + s.root_evals + 50);
  for (int i = 0; i < r.num_rows(); i += 1000) {
    EXPECT_DOUBLE_EQ(r.at(i, 1), 0.1 * r.at(i, 0));
    EXPECT_EQ(r.at(i, 4), r.at(i, 1));
  }
}

TEST(MechanismBlockTest, SensorsAreCheckedAtConstruction) {
  EXPECT_THROW(MechanismBlock("p", Pendulum(0.0), {Sensor("q", mech::SensorKind::kCoordinate, 3)}), InputError);
  EXPECT_THROW(MechanismBlock("p", Pendulum(0.0), {Sensor("r", mech::SensorKind::kReactionForce, -1)}), InputError);
  EXPECT_THROW(MechanismBlock("p", Pendulum(0.0), {ElementSensor("f", 0, 0)}), InputError);
  EXPECT_THROW(MechanismBlock("p", Pendulum(0.0), {Sensor("w", mech::SensorKind::kBodyAngularVelocity, 1, 3)}),
               InputError);
  EXPECT_THROW(MechanismBlock("p", Pendulum(0.0),
                              {Sensor("q", mech::SensorKind::kCoordinate, 0), Sensor("q", mech::SensorKind::kVelocity, 0)}),
               InputError);
  EXPECT_NO_THROW(MechanismBlock("p", Pendulum(0.0), {Sensor("base", mech::SensorKind::kPointPosition, 0)}));
}

TEST(MechanismBlockTest, BodyAnglesAreCardan123) {
  // A body on three revolutes about x, y', z'' (Cardan 1-2-3) reads back its
  // coordinates as angles.
  mech::ModelBuilder m;
  m.AddBody(mech::testing::Box("B", 1.0, {0.1, 0.2, 0.3}));
  m.AddJoint(mech::testing::ChainJoint("j", "Base0", "B",
                                       {Et(T::kRv, mech::Vec3::UnitX(), 2.5), Et(T::kRv, mech::Vec3::UnitY(), -1.2),
                                        Et(T::kRv, mech::Vec3::UnitZ(), -3.0)}));
  auto mechanism = Make(&m);
  const MechanismBlock block("m", mechanism, {Sensor("angles", mech::SensorKind::kBodyAngles, 1)});
  mech::MechanismWorkspace ws(*mechanism);
  std::vector<double> x(mechanism->num_states()), modes(mechanism->num_modes()), out(3);
  mech::InitialState(*mechanism, {}, x, modes, &ws);
  mech::EvaluatePositions(*mechanism, 0.0, x, &ws);
  mech::EvaluateSensor(*mechanism, ws, x, Sensor("angles", mech::SensorKind::kBodyAngles, 1), out);
  EXPECT_NEAR(out[0], 2.5, 1e-14);
  EXPECT_NEAR(out[1], -1.2, 1e-14);
  EXPECT_NEAR(out[2], -3.0, 1e-14);
}

TEST(MechanismBlockTest, RunTimeMethodsDoNotAllocate) {
  // A four-bar (a cut joint: KKT solve and projection) with a spring-damper on
  // the crank and a bang-bang torque (element state, mode, crossing), plus a
  // floating ball (quaternion) pushed by the input F.
  mech::ModelBuilder m;
  auto bar = [](const std::string& name, double length) {
    return mech::testing::Box(name, length, {0.01, 0.5 * length, 0.01}, mech::Vec3(0, 0.5 * length, 0));
  };
  m.AddBody(bar("Crank", 0.3));
  m.AddBody(bar("Coupler", 0.8));
  m.AddBody(bar("Rocker", 0.6));
  m.AddBody(mech::testing::Box("Ball", 0.5, {0.1, 0.1, 0.1}));
  m.AddJoint(mech::testing::ChainJoint("j1", "Base0", "Crank", {Et(T::kRv, mech::Vec3::UnitX(), 1.2, 6.0)}));
  m.AddJoint(mech::testing::ChainJoint("j2", "Crank", "Coupler",
                                       {Et(T::kTc, mech::Vec3::UnitY(), 0.3), Et(T::kRv, mech::Vec3::UnitX(), -1.0)}));
  m.AddJoint(mech::testing::ChainJoint("j3", "Base0", "Rocker",
                                       {Et(T::kTc, mech::Vec3::UnitY(), 0.7), Et(T::kRv, mech::Vec3::UnitX(), 1.9)}));
  mech::JointSpec close = mech::testing::ChainJoint(
      "j4", "Coupler", "Rocker", {Et(T::kTc, mech::Vec3::UnitY(), 0.8), Et(T::kRv, mech::Vec3::UnitX())});
  close.frame2 = mech::Pose::Translation(mech::Vec3(0, 0.6, 0));
  m.AddJoint(close);
  mech::JointSpec free;
  free.name = "float";
  free.body1 = "Base0";
  free.body2 = "Ball";
  free.quaternion = true;
  free.quaternion_initial.angular_velocity = mech::Vec3(1.0, 2.0, 3.0);
  m.AddJoint(free);
  auto model = m.Build();
  const int ball = model->FindBody("Ball");
  std::vector<std::unique_ptr<mech::ForceElement>> elements;
  elements.push_back(std::make_unique<mech::JointForce>(
      "spring", "test", model->dofs()[0], std::make_unique<mech::LinearLaw>(5.0, 1.0, 0.1, 0.0)));
  elements.push_back(std::make_unique<BangBang>(model->dofs()[0], 0.5));
  elements.push_back(std::make_unique<mech::AppliedForce>(
      "push", "test", ball, mech::Vec3(0.1, 0, 0),
      std::array<mech::Parameter, 3>{InputParameter(1.0), mech::Parameter(0.0), InputParameter(2.0)},
      std::array<mech::Parameter, 3>{}, true));
  auto mechanism = std::make_shared<mech::Mechanism>(model, std::move(elements), std::vector<std::string>{"F"});
  using K = mech::SensorKind;
  const std::vector<mech::SensorSpec> sensors = {
      Sensor("q", K::kCoordinate, 0), Sensor("v", K::kVelocity, 0), Sensor("a", K::kAcceleration, 0),
      Sensor("rf", K::kReactionForce, 3), Sensor("rt", K::kReactionTorque, 0, 1), ElementSensor("spring", 0, 0),
      PointSensor("p", K::kPointPosition, ball, mech::Vec3(0.1, 0, 0)),
      PointSensor("pv", K::kPointVelocity, 2, mech::Vec3(0, 0.8, 0)),
      PointSensor("pa", K::kPointAcceleration, ball, mech::Vec3(0.1, 0, 0)), Sensor("angles", K::kBodyAngles, ball),
      Sensor("w", K::kBodyAngularVelocity, ball)};
  DiagramBuilder builder;
  builder.AddBlock(std::make_unique<ConstantBlock>("c", std::vector<double>{2.0}));
  auto owned = std::make_unique<MechanismBlock>("m", mechanism, sensors);
  const MechanismBlock& block = *owned;
  builder.AddBlock(std::move(owned));
  builder.Connect("c", "m.F");
  auto diagram = builder.Build();
  const Diagram& d = *diagram;
  const int b = d.FindBlock("m");
  ASSERT_TRUE(block.has_projection());

  Context ctx;
  ctx.signals.assign(d.num_signals(), 0.0);
  ctx.discrete.assign(d.num_discrete_states(), 0.0);
  std::vector<double> x(d.num_states()), xdot(x.size()), crossings(std::max(1, d.num_zero_crossings()));
  std::vector<double> correction(x.size());
  ctx.x = x.data();
  ctx.xdot = xdot.data();
  ctx.crossings = crossings.data();
  InitializeStates(d, &ctx);
  ASSERT_TRUE(SettleModes(d, &ctx));
  const BlockContext bctx(&ctx, &d.layout(b));
  const std::vector<double> x0 = x;

  constexpr int kCalls = 500;
  long new_calls = 0;
  double largest_correction = 0.0;
  {
    CountAllocations counter;
    for (int i = 0; i < kCalls; ++i) {
      ctx.time = 1e-3 * i;
      // as the solver's right-hand side and root function call them
      ++ctx.evaluation;
      EvaluateOutputs(d, &ctx);
      EvaluateDerivatives(d, &ctx);
      EvaluateZeroCrossings(d, &ctx);
      // every port on its own (positions-only and full paths), then the
      // derivatives and the crossings without outputs first
      for (int port = 0; port < block.num_outputs(); ++port) {
        ++ctx.evaluation;
        block.CalcOutput(port, bctx);
      }
      ++ctx.evaluation;
      block.CalcDerivatives(bctx);
      ++ctx.evaluation;
      block.CalcZeroCrossings(bctx);
      // a state off the manifold: projection corrects it
      for (std::size_t k = 0; k < x.size(); ++k) x[k] = x0[k] + 1e-6 * std::sin(1.0 + i + 3.0 * k);
      ++ctx.evaluation;
      block.Project(bctx, correction, {}, {});
      for (std::size_t k = 0; k < x.size(); ++k) {
        largest_correction = std::max(largest_correction, std::abs(correction[k]));
        x[k] += correction[k];
      }
      // an event: the mode switches
      ++ctx.evaluation;
      block.OnZeroCrossing(0, i % 2 ? 1 : -1, bctx);
    }
    new_calls = counter.calls();
  }
  EXPECT_EQ(new_calls, 0) << "operator new called in " << kCalls << " rounds of the mechanism block's run-time methods";
  EXPECT_GT(largest_correction, 1e-8) << "projection did nothing";
  EXPECT_GT(block.worst_constraint_residual(ctx, b), 0.0);

  // The derivatives reuse the solve of an acceleration port in the same
  // evaluation: the same numbers as solving again.
  ++ctx.evaluation;
  EvaluateOutputs(d, &ctx);
  EvaluateDerivatives(d, &ctx);
  const std::vector<double> reused = xdot;
  std::fill(xdot.begin(), xdot.end(), 0.0);
  ++ctx.evaluation;
  block.CalcDerivatives(bctx);
  EXPECT_EQ(xdot, reused);
}

}  // namespace
}  // namespace mechflow::blocks
