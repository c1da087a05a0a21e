// Force analysis: an element of a diagram driven alone as
// x = x0 + a sin(2 pi f t), against closed forms -- a spring-damper's
// dynamic stiffness and phase, the loop of dry friction -- and the EF2-4
// table of docs/ELEMENTS.md 3.8 through the seed's own diagram.
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "analysis/force_analysis.h"
#include "tests/numbers.h"
#include "tests/test_util.h"

namespace mechflow::analysis {
namespace {

using ::testing::HasSubstr;

using mechflow::testing::kPi;

// A diagram file with one body on a slider and the element `element`
// (named e) between the ground and it, written to a temporary folder.
std::string WriteDiagram(const std::string& name, const std::string& element) {
  const auto dir = std::filesystem::temp_directory_path() / "mechflow_force_analysis_test";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / (name + ".xml")).string();
  std::ofstream(path) << "<diagram name='" << name << "'><identifiers><identifier name='c' value='400'/>"
                      << "<identifier name='d' value='3'/><identifier name='F' value='2'/></identifiers>"
                      << "<mechanism name='m' gravity='0 0 0'><body name='B' mass='1' inertia='1 1 1'/>"
                      << "<joint name='j' type='translational' body1='Base0' body2='B' axis='1 0 0' q0='0.5'/>"
                      << element << "</mechanism><solver t_end='1' rtol='1e-10' atol='1e-12'/></diagram>";
  return path;
}

ForceAnalysisRequest Request(const std::string& path, std::vector<double> amplitudes, std::vector<double> frequencies) {
  ForceAnalysisRequest r;
  r.file = path;
  r.element = "e";
  r.amplitudes = std::move(amplitudes);
  r.frequencies = std::move(frequencies);
  r.cycles = 4;
  r.samples = 800;
  return r;
}

TEST(ForceAnalysisTest, SpringDamperStiffnessAndPhaseAtSeveralFrequencies) {
  // on a line (bipolar) and on a joint coordinate alike
  for (const std::string element :
       {"<force name='e' type='linear' body1='Base0' body2='B' point1='-1 0 0' c='c' d='d'/>",
        "<joint_force name='e' dof='j' type='linear' c='c' d='d'/>"}) {
    const ForceAnalysis fa = RunForceAnalysis(Request(WriteDiagram("spring", element), {1e-3, 5e-3}, {0.5, 2, 10}));
    ASSERT_EQ(fa.cases.size(), 6u);
    for (const ForceAnalysisCase& c : fa.cases) {
      ASSERT_TRUE(c.failure.empty()) << c.failure;
      EXPECT_TRUE(c.periodic);
      const double w = 2 * kPi * c.frequency;
      EXPECT_NEAR(c.stiffness, std::hypot(400.0, 3 * w), 1e-6 * std::hypot(400.0, 3 * w)) << element;
      EXPECT_NEAR(c.phase, std::atan(3 * w / 400.0), 1e-6 * std::atan(3 * w / 400.0)) << element;
      // a damper dissipates pi d w a^2 per cycle, the spring nothing
      EXPECT_NEAR(c.loop_energy, kPi * 3 * w * c.amplitude * c.amplitude, 1e-6 * kPi * 3 * w * c.amplitude * c.amplitude);
    }
  }
}

TEST(ForceAnalysisTest, ContactNormalLawAndABushingComponent) {
  // a points-plane contact with a linear law, 10 mm deep at the start (the
  // body's point 10 mm below the plane), driven 1 mm about that: a
  // spring-damper in the penetration; and a bushing's dx and az components
  const std::string contact =
      "<contact name='e' type='points_plane' body1='B' points='0 0 -0.01' body2='Base0' plane_point='0.5 0 0' "
      "normal='0 0 1' stiffness='c' damping='d'/>";
  ForceAnalysisRequest r = Request(WriteDiagram("contact", contact), {1e-3}, {1, 10});
  ForceAnalysis fa = RunForceAnalysis(r);
  for (const ForceAnalysisCase& c : fa.cases) {
    ASSERT_TRUE(c.failure.empty()) << c.failure;
    const double w = 2 * kPi * c.frequency;
    EXPECT_NEAR(c.x0, 0.01, 1e-12);
    EXPECT_NEAR(c.stiffness, std::hypot(400.0, 3 * w), 1e-6 * std::hypot(400.0, 3 * w));
    EXPECT_NEAR(c.phase, std::atan(3 * w / 400.0), 1e-6);
  }
  const std::string bushing =
      "<bushing name='e' body1='Base0' point1='0.5 0 0' body2='B' c='c 0 0' d='d 0 0' ca='0 0 7' da='0 0 0'/>";
  r = Request(WriteDiagram("bushing", bushing), {1e-3}, {2});
  r.component = "dx";
  fa = RunForceAnalysis(r);
  ASSERT_TRUE(fa.cases[0].failure.empty()) << fa.cases[0].failure;
  EXPECT_NEAR(fa.cases[0].stiffness, std::hypot(400.0, 3 * 4 * kPi), 1e-6 * 400);
  r.component = "az";
  fa = RunForceAnalysis(r);
  ASSERT_TRUE(fa.cases[0].failure.empty()) << fa.cases[0].failure;
  EXPECT_NEAR(fa.cases[0].stiffness, 7.0, 1e-4 * 7);  // small angles: the rotation's sine
  r.component = "qq";
  EXPECT_THAT(testing::InputErrorOf([&] { RunForceAnalysis(r); }), HasSubstr("is not one of a bushing's components"));
  r.component = "";
  EXPECT_THAT(testing::InputErrorOf([&] { RunForceAnalysis(r); }), HasSubstr("needs a component"));
}

TEST(ForceAnalysisTest, DryFrictionLoopArea) {
  // The elastic-friction element with d = 0 is the Jenkins element: loop
  // area 4 F (a - F/c). The Frictional element with an undamped stick
  // spring starts each stick unloaded (its force drops from F to 0 at the
  // turn): 4 a F - F^2/c = 4 F (a - F/(4 c)).
  for (const std::string type : {"frictional", "elastic_friction"}) {
    const std::string element = "<force name='e' type='" + type +
                                "' body1='Base0' body2='B' point1='-1 0 0' friction='F' ratio='1' c='1e5' d='0'/>";
    ForceAnalysisRequest r = Request(WriteDiagram("dry_" + type, element), {1e-3, 3e-3}, {1});
    r.samples = 4000;  // the stick-slip kinks fall inside rows: the sums' error is O(row^2)
    const ForceAnalysis fa = RunForceAnalysis(r);
    for (const ForceAnalysisCase& c : fa.cases) {
      ASSERT_TRUE(c.failure.empty()) << c.failure;
      EXPECT_TRUE(c.periodic) << type;
      const double area = 4 * 2.0 * (c.amplitude - 2.0 / (type == "frictional" ? 4e5 : 1e5));
      EXPECT_NEAR(c.loop_energy, area, 1e-6 * area) << type << " a = " << c.amplitude;
    }
  }
}

TEST(ForceAnalysisTest, ElasticFriction2TableEF2_4FromTheSeedDiagram) {
  // K and delta against mu = mu0, for amplitudes 1 .. 3 mm and two
  // frequencies: the same numbers every time (the element has no dashpot)
  ForceAnalysisRequest r =
      Request(std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/elast_friction2.xml", {1e-3, 2e-3, 3e-3}, {0.2, 5});
  r.element = "friction";
  r.vary = {{{"ffr", "ffr0"}, {0.0, 0.1, 0.2, 0.3, 0.5}}};
  r.samples = 4000;
  const ForceAnalysis fa = RunForceAnalysis(r);
  const double K[] = {80.00, 82.14, 86.83, 93.95, 117.58}, delta[] = {0, 2.75, 5.09, 6.97, 9.23};
  ASSERT_EQ(fa.cases.size(), 30u);
  for (const ForceAnalysisCase& c : fa.cases) {
    ASSERT_TRUE(c.failure.empty()) << c.failure;
    EXPECT_TRUE(c.periodic);
    const int i = static_cast<int>(std::lround(c.varied[0] * 10)) - (c.varied[0] > 0.4 ? 1 : 0);
    EXPECT_NEAR(c.stiffness, K[i], 6e-3 * K[i]) << "mu " << c.varied[0] << " a " << c.amplitude << " f " << c.frequency;
    EXPECT_NEAR(c.phase * 180 / kPi, delta[i], 0.02) << "mu " << c.varied[0];
  }
}

TEST(ForceAnalysisTest, RefusesWhatItCannotDrive) {
  const std::string path = WriteDiagram("refusals",
                                        "<applied_force name='push' body='B' force='1 0 0'/>"
                                        "<joint_force name='e' dof='j' type='frictional' friction='1' stick='exact'/>");
  ForceAnalysisRequest r = Request(path, {1e-3}, {1});
  r.element = "push";
  EXPECT_THAT(testing::InputErrorOf([&] { RunForceAnalysis(r); }), HasSubstr("has no scalar coordinate"));
  r.element = "e";
  EXPECT_THAT(testing::InputErrorOf([&] { RunForceAnalysis(r); }), HasSubstr("sticks exactly"));
  r.element = "ee";
  EXPECT_THAT(testing::InputErrorOf([&] { RunForceAnalysis(r); }), HasSubstr("no force element 'ee'"));
  r.element = "e";
  r.frequencies = {0};
  EXPECT_THAT(testing::InputErrorOf([&] { RunForceAnalysis(r); }), HasSubstr("frequency must be > 0"));
}

// An amplitude whose numbers overflow gives no figures: the case fails
// saying why, and is never periodic (a NaN compares as no difference).
TEST(ForceAnalysisTest, NumbersThatOverflowFailTheCase) {
  const std::string path =
      WriteDiagram("overflow", "<force name='e' type='linear' body1='Base0' body2='B' point1='-1 0 0' c='c' d='d'/>");
  // R ~ 4e302 and v ~ 6e300 are numbers, their product (the loop energy) is not
  const ForceAnalysis fa = RunForceAnalysis(Request(path, {1e-3, 1e300}, {1}));
  ASSERT_EQ(fa.cases.size(), 2u);
  EXPECT_TRUE(fa.cases[0].failure.empty()) << fa.cases[0].failure;
  EXPECT_TRUE(fa.cases[0].periodic);
  const ForceAnalysisCase& c = fa.cases[1];
  EXPECT_THAT(c.failure, HasSubstr("not a finite number"));
  EXPECT_FALSE(c.periodic);
  for (double v : {c.stiffness, c.phase, c.force_amplitude, c.loop_energy}) EXPECT_EQ(v, 0.0);
  EXPECT_TRUE(c.reaction.empty());
  // a drive whose own acceleration a (2 pi f)^2 overflows is known before any run
  EXPECT_THAT(testing::InputErrorOf([&] { RunForceAnalysis(Request(path, {1e306}, {1000})); }),
              HasSubstr("acceleration a (2 pi f)^2 overflows"));
}

TEST(ForceAnalysisTest, AnInterruptEndsItWithTheCasesFinished) {
  ForceAnalysisRequest r = Request(
      WriteDiagram("interrupt", "<joint_force name='e' dof='j' type='linear' c='c' d='d'/>"), {1e-3, 2e-3}, {1, 2});
  volatile std::sig_atomic_t flag = SIGINT;  // came before the first case
  r.interrupt = &flag;
  const ForceAnalysis fa = RunForceAnalysis(r);
  EXPECT_EQ(fa.interrupted, SIGINT);
  EXPECT_TRUE(fa.cases.empty());
  EXPECT_EQ(fa.planned, 4u);
  flag = 0;
  const ForceAnalysis whole = RunForceAnalysis(r);
  EXPECT_EQ(whole.interrupted, 0);
  EXPECT_EQ(whole.cases.size(), 4u);
}

}  // namespace
}  // namespace mechflow::analysis
