// Exact stick of contacts (mech/contact_stick.h): the holds the holding
// forces keep still really keep still along the motion the mechanism
// computes, for points-plane and circle-plane contacts on a body that moves
// in every direction.

#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "mech/circle_plane_contact.h"
#include "mech/mechanism.h"
#include "mech/points_plane_contact.h"
#include "tests/mech/mech_test_util.h"

namespace mechflow::mech::contact_stick_test {
namespace {

using testing::Box;

ContactLaw ExactLaw() {
  ContactLaw law;
  law.stiffness = 1e5;
  law.damping = 300;
  law.mu = 0.4;
  law.mu_static = 0.5;
  law.exact_stick = true;
  return law;
}

// A free box (quaternion joint) whose bottom face lies a little inside a
// tilted plane, turning and moving at random.
std::shared_ptr<const Model> FreeBox() {
  ModelBuilder b;
  b.AddBody(Box("Box", 2.0, {0.05, 0.05, 0.05}));
  JointSpec q;
  q.name = "j";
  q.body1 = "Base0";
  q.body2 = "Box";
  q.quaternion = true;
  b.AddJoint(q);
  return b.Build();
}

// d/dt of each stuck hold's velocity, by central differences along x' (which
// the holding forces computed), against the hold's acceleration: zero.
void ExpectHoldsStill(const Mechanism& mechanism, std::vector<double> x, std::vector<double> modes) {
  MechanismWorkspace ws(mechanism);
  std::vector<double> xdot(mechanism.num_states());
  EvaluateMechanism(mechanism, 0.0, x, {}, modes, &ws, xdot);
  ASSERT_FALSE(ws.stick.stuck.empty());
  auto hold_velocity = [&](const std::vector<double>& at, int g) {
    EvaluatePositions(mechanism, 0.0, at, &ws);
    const int e = mechanism.hold_element(g);
    return mechanism.element(e).HoldVelocity(MakeElementContext(mechanism, 0.0, at, modes, ws, e),
                                             g - mechanism.hold_offset(e));
  };
  const std::vector<int> stuck = ws.stick.stuck;
  const double h = 1e-6;
  std::vector<double> plus = x, minus = x;
  for (std::size_t i = 0; i < x.size(); ++i) plus[i] += h * xdot[i], minus[i] -= h * xdot[i];
  for (const int g : stuck) {
    const double rate = (hold_velocity(plus, g) - hold_velocity(minus, g)) / (2 * h);
    EXPECT_NEAR(rate, 0.0, 1e-6) << "hold " << g;
  }
}

TEST(ContactStickTest, PointsPlaneHoldsStayStillOnAMovingBox) {
  const auto model = FreeBox();
  std::vector<std::unique_ptr<ForceElement>> elements;
  const double a = 0.05;
  const Vec3 normal = Vec3(0.1, -0.3, 1.0).normalized();
  elements.push_back(std::make_unique<PointsPlaneContact>(
      "c", "", 1, std::vector<Vec3>{{-a, -a, -a}, {a, -a, -a}, {-a, a, -a}, {a, a, -a}}, 0, Vec3::Zero(), normal,
      ExactLaw()));
  const Mechanism mechanism(model, std::move(elements), {});
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 5; ++trial) {
    std::vector<double> x(mechanism.num_states(), 0.0), modes(mechanism.num_modes(), 0.0);
    // the box slightly turned, its centre a little less than a above the plane
    Eigen::Quaterniond turn(Eigen::AngleAxisd(0.02 * u(rng), Vec3::UnitX()) *
                            Eigen::AngleAxisd(0.02 * u(rng), Vec3::UnitY()));
    const Eigen::Quaterniond tilt = Eigen::Quaterniond::FromTwoVectors(Vec3::UnitZ(), normal) * turn;
    const Vec3 centre = (a - 2e-4) * normal;
    for (int k = 0; k < 3; ++k) x[k] = centre(k);
    x[3] = tilt.w(), x[4] = tilt.x(), x[5] = tilt.y(), x[6] = tilt.z();
    for (int k = 0; k < 6; ++k) x[7 + k] = 0.5 * u(rng);
    for (int i = 0; i < 4; ++i) modes[i] = 1.0;  // touching, stuck (the stick modes stay 0)
    ExpectHoldsStill(mechanism, x, modes);
  }
}

TEST(ContactStickTest, CirclePlaneHoldRollsARollingDisk) {
  const auto model = FreeBox();
  std::vector<std::unique_ptr<ForceElement>> elements;
  const Vec3 normal = Vec3(0.0, -0.2, 1.0).normalized();
  elements.push_back(std::make_unique<CirclePlaneContact>("d", "", 1, Vec3::Zero(), Vec3(1.0, 0.2, 0.1), 0.1, 0,
                                                          Vec3::Zero(), normal, ExactLaw()));
  const Mechanism mechanism(model, std::move(elements), {});
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 5; ++trial) {
    std::vector<double> x(mechanism.num_states(), 0.0), modes(mechanism.num_modes(), 0.0);
    const Vec3 centre = (0.1 - 1e-4) * normal;
    for (int k = 0; k < 3; ++k) x[k] = centre(k);
    x[3] = 1.0;
    for (int k = 0; k < 6; ++k) x[7 + k] = 2.0 * u(rng);
    modes[0] = 1.0;
    ExpectHoldsStill(mechanism, x, modes);
  }
}

}  // namespace
}  // namespace mechflow::mech::contact_stick_test
