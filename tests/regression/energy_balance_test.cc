// Energy accounting: every element integrates the work it
// does on the bodies (the power of its loads), springs report their stored
// energy and friction and damping elements what they dissipated. Checks:
//   - the energy balance (kinetic + gravitational energy gained minus all
//     element work) stays at the integration's error in every example whose
//     motion no clock prescribes;
//   - where every element knows its stored energy, kinetic + gravitational +
//     stored energy only falls, by exactly what the elements dissipated;
//   - the Coulomb oscillator FR-2 dissipates F times its path, 5.5 J.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "tests/test_util.h"

namespace mechflow {
namespace {

// `xml` with the sensors (inside its mechanism) logged under their own names.
std::string WithSensors(std::string xml, const std::vector<std::string>& sensors) {
  const auto name_at = xml.find("\"", xml.find("name=", xml.find("<mechanism"))) + 1;
  const std::string mechanism = xml.substr(name_at, xml.find('"', name_at) - name_at);
  std::string declared, logged;
  for (const std::string& s : sensors) {
    const std::string name = s.substr(0, s.find(' '));
    declared += "<sensor name=\"" + name + "\" " + s.substr(s.find(' ') + 1) + "/>";
    logged += "<log signal=\"" + mechanism + "." + name + "\" label=\"" + name + "\"/>";
  }
  xml.insert(xml.find("</output>"), logged);
  xml.insert(xml.find("</mechanism>"), declared);
  return xml;
}

double Largest(const std::vector<double>& values) {
  double m = 0.0;
  for (double v : values) m = std::max(m, std::abs(v));
  return m;
}

class BalancedExample : public ::testing::TestWithParam<const char*> {};

// "oscillations.xml+exact": the example with its contacts' regularised law
// replaced by exact stick (their v_eps by stick="exact").
std::string ExampleText(const std::string& name) {
  const std::size_t plus = name.find('+');
  const std::string xml = testing::ReadExample(name.substr(0, plus));
  return plus == std::string::npos ? xml : testing::WithExactStick(xml);
}

TEST_P(BalancedExample, EnergyGainedEqualsTheElementsWork) {
  diagrams::LoadOptions options;
  const std::string name = GetParam();
  // Frequencies runs 8 s for its spectrum; the bound below is for its first 2
  if (name == "frequencies.xml") options.t_end = 2.0;
  // read as the example's own file, so the parts it includes are found beside it
  const testing::XmlRun run = testing::RunDescription(
      diagrams::ReadDiagramText(
          WithSensors(ExampleText(name),
                      {"T kind=\"kinetic_energy\"", "V kind=\"potential_energy\"", "balance kind=\"energy_balance\""}),
          std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/" + name.substr(0, name.find('+'))),
      options);
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto T = run.Column("T"), V = run.Column("V"), balance = run.Column("balance");
  std::vector<double> gained(T.size());
  for (std::size_t i = 0; i < T.size(); ++i) gained[i] = T[i] + V[i] - T[0] - V[0];
  const double scale = std::max(Largest(T), Largest(gained));
  ASSERT_GT(scale, 1e-6) << "the example should move";
  const double error = Largest(balance), rtol = run.loaded.solver.rtol;
  std::cout << GetParam() << ": energy balance error " << error / scale << " of the energy exchanged at rtol "
            << rtol << "\n";
  // Measured 3e-10 .. 1.1e-5 (falling.xml at rtol 1e-6); the most in units
  // of rtol is frequencies.xml, 2800 rtol: 134 undamped periods at 67 Hz,
  // over which BDF's error adds up (it falls 7-8x per decade of rtol).
  EXPECT_LT(error, 5e3 * rtol * scale) << GetParam();
  EXPECT_LT(std::abs(balance[0]), 1e-12 * scale);
}

INSTANTIATE_TEST_SUITE_P(Examples, BalancedExample,
                         ::testing::Values("damping_ratio.xml", "elast_friction.xml", "elast_friction2.xml",
                                           "falling.xml", "forces.xml", "frequencies.xml", "oscillations.xml",
                                           "rollers.xml", "math_game.xml", "convel1.xml", "fidget.xml",
                                           "tension_mechanism.xml", "four_bar.xml", "slider_crank.xml", "train.xml",
                                           "oscillations.xml+exact", "falling.xml+exact", "fidget.xml+exact"));

// Kinetic + gravitational + stored energy, and what the elements dissipated,
// from the ElastFriction example (box on a spring, friction to the base).
// The integration's error in the energy accounts at the example's rtol 1e-8:
// at most 1.5e-6 of the energy measured (the elastic-friction element's
// ringing after the stop; 2.4e-8 at rtol 1e-10).
constexpr double kAccounting = 3e-6;

struct EnergyHistory {
  std::vector<double> total, dissipated;
};

EnergyHistory ElastFrictionEnergy(const std::string& variant, const std::string& type, const std::string& friction) {
  diagrams::LoadOptions options;
  options.variants = {variant, type};
  // the spring as the linear law it is without its excitation (q = 0 in
  // these variants), whose energy is known
  std::string xml = testing::ReadExample("elast_friction.xml");
  const std::string expression = "type=\"expression\" body1=\"Base\" point1=\"0 0 0\" body2=\"Box\"\n"
                                 "           expression=\"-cspring*(x-1)+q*sin(2*pi*freq*t)\"";
  EXPECT_NE(xml.find(expression), std::string::npos);
  xml.replace(xml.find(expression), expression.size(),
              "type=\"linear\" body1=\"Base\" point1=\"0 0 0\" body2=\"Box\" c=\"cspring\" x0=\"1\"");
  const testing::XmlRun run = testing::RunXml(
      WithSensors(xml,
                  {"T kind=\"kinetic_energy\"", "V kind=\"potential_energy\"",
                   "Us kind=\"element\" element=\"spring\" quantity=\"energy\"",
                   "Uf kind=\"element\" element=\"" + friction + "\" quantity=\"energy\"",
                   "Df kind=\"element\" element=\"" + friction + "\" quantity=\"dissipated\"",
                   "Ds kind=\"element\" element=\"spring\" quantity=\"dissipated\""}),
      options);
  EXPECT_TRUE(run.outcome.ok) << run.outcome.failure;
  EnergyHistory h;
  const auto T = run.Column("T"), V = run.Column("V"), Us = run.Column("Us"), Uf = run.Column("Uf"),
             Df = run.Column("Df"), Ds = run.Column("Ds");
  for (std::size_t i = 0; i < T.size(); ++i) {
    h.total.push_back(T[i] + V[i] + Us[i] + Uf[i]);
    h.dissipated.push_back(Df[i] + Ds[i]);
    EXPECT_LT(std::abs(Ds[i]), kAccounting * (T[0] + Us[0])) << "an undamped spring dissipates nothing: " << variant
                                                       << "/" << type << " row " << i;
  }
  return h;
}

TEST(EnergyAccountingTest, FrictionOnlyTakesEnergyAndSaysHowMuch) {
  for (const char* variant : {"Free", "Simple spring"}) {
    for (const auto& [type, element] : {std::pair{"Standard", "friction"}, std::pair{"Elastic", "elastic"}}) {
      const EnergyHistory h = ElastFrictionEnergy(variant, type, element);
      ASSERT_GT(h.total.size(), 10u);
      const double e0 = h.total[0];
      for (std::size_t i = 1; i < h.total.size(); ++i) {
        EXPECT_LE(h.total[i], h.total[i - 1] + kAccounting * e0) << variant << "/" << type << " row " << i;
        EXPECT_GE(h.dissipated[i], h.dissipated[i - 1] - kAccounting * e0) << variant << "/" << type << " row " << i;
        EXPECT_NEAR(h.total[i] + h.dissipated[i], e0, kAccounting * e0) << variant << "/" << type << " row " << i;
      }
      // Free: the box's 11.25 J all go; Simple spring (FR-2): all but the
      // 0.0125 J left in the spring at x = -0.005 m
      const double expected = std::string(variant) == "Free" ? 11.25 : 5.5;
      EXPECT_NEAR(h.dissipated.back(), expected, 2e-3 * expected) << variant << "/" << type;
    }
  }
}

TEST(EnergyAccountingTest, ExactStickDissipatesFrictionTimesPath) {
  // FR-2 with exact stick: the path is 0.19 + 0.15 + 0.11 + 0.07 + 0.03 m
  const testing::XmlRun run = testing::RunXml(
      "<diagram name='fr2'><mechanism name='m' gravity='0 0 0'>"
      "<body name='Box' mass='10' inertia='1 1 1'/>"
      "<joint name='j' type='translational' body1='Base0' body2='Box' axis='1 0 0' q0='0.105'/>"
      "<joint_force name='spring' dof='j' type='linear' c='1000' x0='0'/>"
      "<joint_force name='friction' dof='j' type='frictional' friction='10' ratio='1.2' stick='exact'/>"
      "<sensor name='D' kind='element' element='friction' quantity='dissipated'/>"
      "<sensor name='U' kind='element' element='spring' quantity='energy'/>"
      "<sensor name='balance' kind='energy_balance'/></mechanism>"
      "<solver t_end='3' rtol='1e-10' atol='1e-12'/>"
      "<output interval='0.01'><log signal='m.D'/><log signal='m.U'/><log signal='m.balance'/></output></diagram>");
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  // measured at rtol 1e-10: D 2.4e-8 J below 5.5 J, the balance within 1.05e-7 J
  EXPECT_NEAR(run.Column("m.D").back(), 10 * 0.55, 1e-7);
  EXPECT_NEAR(run.Column("m.U").back(), 0.5 * 1000 * 0.005 * 0.005, 1e-8);
  EXPECT_LT(Largest(run.Column("m.balance")), 5e-7);
}

TEST(EnergyAccountingTest, AVaryingStiffnessHasNoStoredEnergyToReport) {
  const std::string message = testing::InputErrorOf([] {
    testing::LoadXml(
        "<diagram><mechanism name='m' gravity='0 0 0'><body name='B' mass='1' inertia='1 1 1'/>"
        "<joint name='j' type='translational' body1='Base0' body2='B' axis='1 0 0'/>"
        "<joint_force name='s' dof='j' type='linear' c='100*(1+t)'/>"
        "<sensor name='D' kind='element' element='s' quantity='dissipated'/></mechanism>"
        "<solver t_end='1'/></diagram>");
  });
  EXPECT_NE(message.find("has no output 'dissipated'"), std::string::npos) << message;
  EXPECT_NE(message.find("work"), std::string::npos) << message;
}

TEST(EnergyAccountingTest, ContactsStoreAndDissipate) {
  // Falling: a cube drops onto an incline and a floor (stiff contacts with
  // damping and friction); nothing else acts but gravity.
  const testing::XmlRun run = testing::RunXml(WithSensors(
      testing::ReadExample("falling.xml"),
      {"T kind=\"kinetic_energy\"", "V kind=\"potential_energy\"",
       "U1 kind=\"element\" element=\"incline\" quantity=\"energy\"",
       "U2 kind=\"element\" element=\"floor\" quantity=\"energy\"",
       "D1 kind=\"element\" element=\"incline\" quantity=\"dissipated\"",
       "D2 kind=\"element\" element=\"floor\" quantity=\"dissipated\""}));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto T = run.Column("T"), V = run.Column("V"), U1 = run.Column("U1"), U2 = run.Column("U2"),
             D1 = run.Column("D1"), D2 = run.Column("D2");
  const double e0 = T[0] + V[0] + U1[0] + U2[0];
  double most_stored = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < T.size(); ++i) scale = std::max(scale, std::abs(T[i] + V[i] - T[0] - V[0]));
  ASSERT_GT(scale, 1.0);
  for (std::size_t i = 1; i < T.size(); ++i) {
    most_stored = std::max(most_stored, U1[i] + U2[i]);
    const double total = T[i] + V[i] + U1[i] + U2[i];
    // rtol 1e-6 here: the accounts close to 2e-5 of the energy exchanged
    EXPECT_NEAR(total + D1[i] + D2[i], e0, 2e-5 * scale) << "row " << i;
    EXPECT_GE(D1[i] + D2[i], D1[i - 1] + D2[i - 1] - 2e-5 * scale) << "row " << i;
  }
  EXPECT_GT(most_stored, 1e-6) << "the contacts should take load";
  EXPECT_GT(D1.back() + D2.back(), 0.1 * scale) << "impacts and sliding dissipate";
}

// A mechanism without a degree of freedom: a clock drives the body up and
// down, z = A sin(w t), against gravity and a linear damper d to the ground.
// Its elements' work is integrated all the same (the work states are the
// only states): the damper takes
//   D(t) = d A^2 w^2 (t/2 + sin(2 w t)/(4 w)),
// its work is -D, and the drive's work balances the rest (energy_balance 0).
TEST(EnergyAccountingTest, ADampedMotionThatAClockDrivesDissipatesInItsDamper) {
  const double A = 0.1, w = 2 * std::numbers::pi, d = 20.0, m = 2.0;
  const testing::XmlRun run = testing::RunXml(
      "<diagram name='driven'><mechanism name='m' gravity='0 0 -9.81'>"
      "<body name='B' mass='2' inertia='1 1 1'/>"
      "<joint name='j' type='generalized' body1='Base0' body2='B'>"
      "<et type='tt' axis='0 0 1' value='0.1*sin(2*pi*t)'/></joint>"
      "<force name='damper' type='linear' body1='Base0' point1='0 0 -1' body2='B' c='0' d='20'/>"
      "<sensor name='W' kind='element' element='damper' quantity='work'/>"
      "<sensor name='D' kind='element' element='damper' quantity='dissipated'/>"
      "<sensor name='T' kind='kinetic_energy'/>"
      "<sensor name='balance' kind='energy_balance'/></mechanism>"
      "<solver t_end='1.3' rtol='1e-8' atol='1e-10'/>"
      "<output interval='0.01'><log signal='m.W'/><log signal='m.D'/><log signal='m.T'/>"
      "<log signal='m.balance'/></output></diagram>");
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto t = run.Column("time"), W = run.Column("m.W"), D = run.Column("m.D"), T = run.Column("m.T"),
             balance = run.Column("m.balance");
  ASSERT_EQ(t.size(), 131u);
  const double most = d * A * A * w * w * (1.3 / 2 + 1.0 / (4 * w));  // above D(t) on [0, 1.3]
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double dissipated = d * A * A * w * w * (t[i] / 2 + std::sin(2 * w * t[i]) / (4 * w));
    const double v = A * w * std::cos(w * t[i]);
    // at rtol 1e-8 (the work is a state, so under the solver's error control)
    EXPECT_NEAR(D[i], dissipated, 1e-6 * most) << "t = " << t[i];
    EXPECT_NEAR(W[i], -dissipated, 1e-6 * most) << "t = " << t[i];
    EXPECT_NEAR(T[i], 0.5 * m * v * v, 1e-9 * most) << "t = " << t[i];
    EXPECT_NEAR(balance[i], 0.0, 1e-6 * most) << "t = " << t[i];
  }
}

}  // namespace
}  // namespace mechflow
