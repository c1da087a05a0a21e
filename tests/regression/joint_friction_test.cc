// Friction on a joint coordinate (docs/ELEMENTS.md 3.6): the frictional element
// on a revolute joint (a friction moment) and on a prismatic joint (a
// force), against the Coulomb oscillator's closed form: with stiffness k and
// friction F, every half period pi sqrt(I/k) the amplitude falls by 2 F / k,
// and the motion stops for good at the first turning point within F / k of
// the spring's rest. The friction may come from a signal (an identifier
// input), here a block that reads the joint's own reaction force.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/numbers.h"
#include "tests/test_util.h"

namespace mechflow {
namespace {

using mechflow::testing::kPi;

std::string Oscillator(const std::string& joint_type, const std::string& friction, const std::string& extra = "") {
  return "<diagram name='osc'><identifiers><identifier name='k' value='100'/><identifier name='F' value='2'/>"
         "</identifiers><mechanism name='m' gravity='0 0 0'>"
         "<body name='B' mass='1' inertia='1 1 1'/>" +
         extra +
         "<joint name='j' type='" + joint_type + "' body1='Base0' body2='B' axis='0 0 1' q0='1'/>"
         "<joint_force name='spring' dof='j' type='linear' c='k' x0='0'/>"
         "<joint_force name='bearing' dof='j' type='frictional' friction='" + friction +
         "' ratio='1' c='1e6' d='1000'/>"
         "<sensor name='q' kind='coordinate' dof='j'/><sensor name='mode' kind='element' element='bearing' "
         "quantity='mode'/><sensor name='friction' kind='element' element='bearing' quantity='force'/>"
         "</mechanism><solver t_end='10' rtol='1e-9' atol='1e-11'/>"
         "<output interval='0.0005'><log signal='m.q'/><log signal='m.mode'/><log signal='m.friction'/></output>"
         "</diagram>";
}

// Turning points of q on the output grid (where its rate changes sign).
std::vector<double> TurningValues(const std::vector<double>& q) {
  std::vector<double> out;
  for (std::size_t i = 1; i + 1 < q.size(); ++i)
    if ((q[i] - q[i - 1]) * (q[i + 1] - q[i]) < 0) out.push_back(q[i]);
  return out;
}

void ExpectCoulombDecay(const testing::XmlRun& run) {
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto q = run.Column("m.q");
  const auto turning = TurningValues(q);
  // 1, -0.96, 0.92, ..., while the amplitude exceeds F / k = 0.02: 24 turning
  // points after the start, then it sticks at 0.02 (>= F/k is not enough to move)
  ASSERT_GE(turning.size(), 20u);
  for (std::size_t n = 0; n < 20; ++n) {
    const double expected = (n % 2 == 0 ? -1.0 : 1.0) * (1.0 - 0.04 * (n + 1));
    // the stick spring (c = 1e6) and the 0.5 ms grid shift a turning point by up to 2e-6
    EXPECT_NEAR(turning[n], expected, 5e-6) << "turning point " << n + 1;
  }
  EXPECT_LE(std::abs(q.back()), 0.02 + 1e-6);
  EXPECT_EQ(run.Column("m.mode").back(), 0.0) << "stuck at the end";
}

TEST(JointFrictionTest, ACoulombMomentOnAHingeDampsAsTheClosedForm) {
  ExpectCoulombDecay(testing::RunXml(Oscillator("rotational", "F")));
}

TEST(JointFrictionTest, ACoulombForceOnASliderDampsAsTheClosedForm) {
  ExpectCoulombDecay(testing::RunXml(Oscillator("translational", "F")));
}

TEST(JointFrictionTest, TheFrictionForceFollowsASignal) {
  // F = 2 again, now fed to the bearing through an identifier input from a
  // constant block: the element reads it at every evaluation
  const std::string diagram = Oscillator("rotational", "Fin", "<input name='Fin'/>");
  std::string xml = diagram;
  xml.replace(xml.find("<identifier name='F' value='2'/>"), 0, "<identifier name='Fin' value='0'/>");
  xml.replace(xml.find("</diagram>"), 0,
              "<blocks><block type='constant' name='normal' value='2'/></blocks>"
              "<connections><connect from='normal.y' to='m.Fin'/></connections>");
  ExpectCoulombDecay(testing::RunXml(xml));
}

TEST(JointFrictionTest, FrictionFromTheGuidesOwnReactionIsAnAlgebraicLoopSolved) {
  // A slider on a vertical guide (z), pressed against it by gravity along
  // -x: the guide's reaction is N = m g = 10 N, and mu = 0.2 gives F = 2 N
  // again. N depends on the accelerations the friction changes: the loop is
  // solved at every evaluation.
  std::string xml = Oscillator("translational", "mu*abs(N)", "<input name='N'/>");
  xml.replace(xml.find("<identifier name='F' value='2'/>"), 0,
              "<identifier name='N' value='0'/><identifier name='mu' value='0.2'/>");
  xml.replace(xml.find("gravity='0 0 0'"), 15, "gravity='-10 0 0'");
  xml.replace(xml.find("</mechanism>"), 0, "<sensor name='guide' kind='reaction_force' joint='j' component='x'/>");
  xml.replace(xml.find("</diagram>"), 0, "<connections><connect from='m.guide' to='m.N'/></connections>");
  const testing::XmlRun run = testing::RunXml(xml);
  ExpectCoulombDecay(run);
  const auto friction = run.Column("m.friction");
  double largest = 0.0;
  for (double f : friction) largest = std::max(largest, std::abs(f));
  EXPECT_NEAR(largest, 2.0, 1e-6);  // mu N while sliding
}

TEST(JointFrictionTest, ElasticFrictionOnAJointIsRefusedWithWhatToDoInstead) {
  std::string xml = Oscillator("rotational", "F");
  xml.replace(xml.find("type='frictional'"), 17, "type='elastic_friction2'");
  try {
    testing::RunXml(xml);
    FAIL() << "accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("on a joint coordinate use type=\"frictional\""), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace mechflow
