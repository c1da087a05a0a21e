// Fidget seed (ELEMENTS.md 9.6, diagrams/examples/fidget.xml): circle-plane
// contacts work with either sign of the circle normal, the dropped body
// settles to rest with the plunger's joint deflection at -(weight component
// along the joint axis)/c, and its mechanical energy never rises above the
// start (the contacts and the damper only take energy out; the contact
// springs give back no more than they stored) -- with the contacts'
// regularised friction and with exact stick.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "blocks/solver/simulator.h"
#include "diagrams/loader.h"
#include "diagrams/xml_reader.h"
#include "tests/test_util.h"

namespace mechflow::fidget_test {  // names of its own: the files of its folder are compiled together
namespace {

struct FidgetRun {
  std::vector<std::string> names;
  std::vector<std::vector<double>> columns;
  const std::vector<double>& Column(const std::string& name) const {
    for (std::size_t i = 0; i < names.size(); ++i)
      if (names[i] == name) return columns[i];
    throw std::runtime_error("no column " + name);
  }
};

// fidget.xml, with its contacts' v_eps replaced by stick="exact" when `exact`.
FidgetRun RunFidget(double s1, double s2, double s3, bool exact = false) {
  diagrams::LoadOptions options;
  options.overrides = {{"s1", s1}, {"s2", s2}, {"s3", s3}};
  const std::string path = std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/fidget.xml";
  const std::string text = testing::ReadExample("fidget.xml");
  const std::string xml = exact ? testing::WithExactStick(text) : text;
  const auto loaded = diagrams::LoadDiagramDescription(diagrams::ReadDiagramText(xml, path), options);
  blocks::Simulator sim(*loaded.diagram, loaded.solver, loaded.logged);
  const auto outcome = sim.Run();
  EXPECT_TRUE(outcome.ok) << outcome.failure;
  FidgetRun run;
  const auto& r = sim.results();
  for (const char* name : {"time", "m.x", "m.vx", "m.p1[0]", "m.p1[1]", "m.p1[2]", "m.v1[0]", "m.v1[1]", "m.v1[2]",
                           "m.w1[0]", "m.w1[1]", "m.w1[2]", "m.angles1[0]", "m.angles1[1]", "m.angles1[2]",
                           "m.p2[2]", "m.v2[0]", "m.v2[1]", "m.v2[2]", "m.side1_force", "m.side2_force",
                           "m.bottom_force"}) {
    const int c = r.FindColumn(name);
    if (c < 0) throw std::runtime_error(std::string("no column ") + name);
    run.names.push_back(name);
    run.columns.push_back(r.Column(c));
  }
  return run;
}

// the numbers of fidget.xml
constexpr double kM1 = 1.0, kM2 = 0.2, kR = 0.1, kW = 0.03, kL2 = 0.15, kRb = 0.01, kC = 1000.0, kG = 9.81;

TEST(FidgetTest, EitherSignOfTheCircleNormalsGivesTheSameRun) {
  const FidgetRun base = RunFidget(1, -1, 1);
  for (const auto& signs : {std::vector<double>{-1, 1, -1}, std::vector<double>{1, 1, 1}}) {
    const FidgetRun other = RunFidget(signs[0], signs[1], signs[2]);
    for (std::size_t c = 0; c < base.names.size(); ++c) {
      ASSERT_EQ(other.columns[c].size(), base.columns[c].size());
      double worst = 0;
      for (std::size_t k = 0; k < base.columns[c].size(); ++k)
        worst = std::max(worst, std::abs(other.columns[c][k] - base.columns[c][k]));
      // the contact uses only (N.n_c) n_c, unchanged by negating n_c, so the
      // arithmetic is the same: equal to the last bit
      EXPECT_EQ(worst, 0.0) << base.names[c] << " with signs " << signs[0] << " " << signs[1] << " " << signs[2];
    }
  }
}

class FidgetLaw : public ::testing::TestWithParam<bool> {};

TEST_P(FidgetLaw, SettlesWithThePlungerDeflectedByItsWeightOverCAndLosesEnergy) {
  const FidgetRun run = RunFidget(1, -1, 1, GetParam());
  const auto& t = run.Column("time");
  const std::size_t end = t.size() - 1;
  auto at = [&](const std::string& name, std::size_t k) { return run.Column(name)[k]; };
  // all three contacts took load; the body left the floor again after landing (a hop)
  const auto &side1 = run.Column("m.side1_force"), &side2 = run.Column("m.side2_force");
  const auto& bottom = run.Column("m.bottom_force");
  EXPECT_GT(*std::max_element(side1.begin(), side1.end()), 0.0);
  EXPECT_GT(*std::max_element(side2.begin(), side2.end()), 0.0);
  EXPECT_GT(*std::max_element(bottom.begin(), bottom.end()), 0.0);
  std::size_t landed = 0;
  while (landed < end && side1[landed] == 0 && side2[landed] == 0) ++landed;
  bool hopped = false;
  for (std::size_t k = landed + 1; k <= end; ++k) hopped |= side1[k] == 0 && side2[k] == 0 && bottom[k] == 0;
  EXPECT_TRUE(hopped);

  // at rest: nothing moves, the plunger hangs free of the floor
  for (const char* name : {"m.vx", "m.v1[0]", "m.v1[1]", "m.v1[2]", "m.w1[0]", "m.w1[1]", "m.w1[2]"})
    EXPECT_LT(std::abs(at(name, end)), 1e-6) << name;
  EXPECT_EQ(bottom[end], 0.0);
  // joint axis = body 1's Z; with R = Rx(a) Ry(b) Rz(c) its vertical component is cos a cos b
  const double axis_z = std::cos(at("m.angles1[0]", end)) * std::cos(at("m.angles1[1]", end));
  const double expected = -kM2 * kG * axis_z / kC;  // -1.962 mm upright
  // the damper has decayed (e^(-0.1 * 70.7 * 5) ~ 1e-15): the residual is the solver's
  EXPECT_NEAR(at("m.x", end), expected, 1e-6 * std::abs(expected));
  EXPECT_NEAR(axis_z, 1.0, 1e-6);  // settles upright on both rims

  // mechanical energy: kinetic (body inertias in body axes), gravity, plunger spring
  const Eigen::Vector3d i1(kM1 * kR * kR, kM1 * (kR * kR / 2 + 4 * kW * kW / 12), kM1 * (kR * kR / 2 + 4 * kW * kW / 12));
  const Eigen::Vector3d i2(kM2 * kL2 * kL2 / 12, kM2 * kL2 * kL2 / 12, kM2 * kRb * kRb / 2);
  double e0 = 0, worst = -1e300, e_end = 0;
  for (std::size_t k = 0; k <= end; ++k) {
    const double a = at("m.angles1[0]", k), b = at("m.angles1[1]", k), c = at("m.angles1[2]", k);
    const Eigen::Matrix3d rotation = (Eigen::AngleAxisd(a, Eigen::Vector3d::UnitX()) *
                                      Eigen::AngleAxisd(b, Eigen::Vector3d::UnitY()) *
                                      Eigen::AngleAxisd(c, Eigen::Vector3d::UnitZ()))
                                         .toRotationMatrix();
    const Eigen::Vector3d w =
        rotation.transpose() * Eigen::Vector3d(at("m.w1[0]", k), at("m.w1[1]", k), at("m.w1[2]", k));
    const Eigen::Vector3d v1(at("m.v1[0]", k), at("m.v1[1]", k), at("m.v1[2]", k));
    const Eigen::Vector3d v2(at("m.v2[0]", k), at("m.v2[1]", k), at("m.v2[2]", k));
    const double x = at("m.x", k);
    const double e = 0.5 * kM1 * v1.squaredNorm() + 0.5 * kM2 * v2.squaredNorm() +
                     0.5 * w.dot((i1 + i2).cwiseProduct(w)) + kG * (kM1 * at("m.p1[2]", k) + kM2 * at("m.p2[2]", k)) +
                     0.5 * kC * x * x;
    if (k == 0) e0 = e;
    worst = std::max(worst, e - e0);
    e_end = e;
  }
  EXPECT_LE(worst, 1e-8 * e0);
  std::printf("%s: rest deflection %.9e m (expected %.9e), energy %.6f J at start, largest rise %.3e J, end %.6f J\n",
              GetParam() ? "exact stick" : "regularised", at("m.x", end), expected, e0, worst, e_end);
}

INSTANTIATE_TEST_SUITE_P(Friction, FidgetLaw, ::testing::Values(false, true),
                         [](const ::testing::TestParamInfo<bool>& info) {
                           return std::string(info.param ? "ExactStick" : "Regularised");
                         });

}  // namespace
}  // namespace mechflow::fidget_test
