// The mechanism as a block: simulated by CVODE with projection, against
// closed forms.
#include "blocks/library/mechanism_block.h"

#include <cmath>
#include <iostream>

#include <gtest/gtest.h>

#include "blocks/diagram_builder.h"
#include "blocks/simulator.h"
#include "tests/mech/mech_test_util.h"

namespace mechflow::blocks {
namespace {

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
  // Issue 3: a four-bar runs 10 s with the position residual below 1e-8 at rtol 1e-8.
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
  EXPECT_LT(fb->worst_constraint_residual(), 1e-8);
  EXPECT_GT(fb->worst_constraint_residual(), 0.0) << "projection never ran";
  std::cout << "four-bar: worst residual before projection " << fb->worst_constraint_residual() << ", steps "
            << sim.stats().steps << "\n";
}

}  // namespace
}  // namespace mechflow::blocks
