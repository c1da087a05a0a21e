// The static equilibrium of diagrams with switching elements
// (analysis/linearization.h FindEquilibrium): the state found against the end
// of a long damped transient of the same diagram, computed here by the
// simulator, with the modes (contact touching, friction stuck) that the
// transient ends in; the modes reported and the frequencies linearised in
// them; and refusals that name the element whose mode does not settle.

#include <cmath>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "analysis/linearization.h"
#include "blocks/solver/simulator.h"
#include "diagrams/loader.h"
#include "mech/errors.h"
#include "tests/numbers.h"
#include "tests/test_util.h"

namespace mechflow::analysis {
namespace {

using namespace blocks;

using ::testing::HasSubstr;

using mechflow::testing::kPi;

// The state and modes of the last row a run records.
class LastRow : public RowObserver {
 public:
  void OnRow(double t, const double* x, const Context& ctx) override {
    time = t;
    state.assign(x, x + size);
    discrete = ctx.discrete;
  }
  int size = 0;
  double time = 0.0;
  std::vector<double> state, discrete;
};

// Runs the diagram as loaded (its own t_end) and returns its last row.
LastRow Transient(const diagrams::LoadedDiagram& loaded) {
  LastRow last;
  last.size = loaded.diagram->num_states();
  Simulator sim(*loaded.diagram, loaded.solver, loaded.logged);
  sim.SetRowObserver(&last);
  const RunOutcome outcome = sim.Run();
  EXPECT_TRUE(outcome.ok) << outcome.failure;
  EXPECT_DOUBLE_EQ(last.time, loaded.solver.t_end);
  return last;
}

struct Equilibrium {
  diagrams::LoadedDiagram loaded;
  Context ctx;
  std::vector<double> x;
  EquilibriumResult result;

  explicit Equilibrium(diagrams::LoadedDiagram d) : loaded(std::move(d)) {
    PrepareContext(*loaded.diagram, loaded.solver.t_start, &ctx, &x);
  }
  void Find() { result = FindEquilibrium(*loaded.diagram, &ctx, &x); }
  std::vector<std::string> Modes() const { return DescribeLinearisedModes(*loaded.diagram, ctx); }
  std::vector<Mode> Linearise() { return ModalAnalysis(StateJacobian(*loaded.diagram, &ctx, x)); }
};

void ExpectSameState(const std::vector<double>& found, const std::vector<double>& transient, double tolerance) {
  ASSERT_EQ(found.size(), transient.size());
  for (std::size_t i = 0; i < found.size(); ++i) EXPECT_NEAR(found[i], transient[i], tolerance) << "state " << i;
}

TEST(EquilibriumModesTest, LeverPreloadedAgainstABlockRestsOnItsContact) {
  // The lever starts 20 mm clear of the block, its spring's free angle deep
  // inside: in the initial modes (not touching) Newton finds that free angle;
  // the search must touch and find the rest state the transient ends in.
  const std::string file = std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/lever_stop.xml";
  const LastRow transient = Transient(diagrams::LoadDiagram(file));
  Equilibrium eq(diagrams::LoadDiagram(file));
  ASSERT_EQ(eq.ctx.discrete, std::vector<double>{0.0});  // not touching at the start
  eq.Find();
  ExpectSameState(eq.x, transient.state, 1e-6);
  EXPECT_EQ(eq.ctx.discrete, transient.discrete);
  EXPECT_EQ(eq.result.rounds, 2);
  EXPECT_EQ(eq.result.switched, std::vector<std::string>{"lever.stop"});
  ASSERT_EQ(eq.Modes().size(), 1u);
  EXPECT_THAT(eq.Modes()[0], HasSubstr("lever.stop: 1 of 1 point(s) touching"));

  // the contact force, about 52 N, in the model's own terms: c times the
  // tip's depth below the face
  const double l = 0.5, gap = 0.02, c = 1e5, k = 160, m = 1, g = 9.81;
  const double phi = eq.x[0], depth = -gap - l * std::sin(phi);
  EXPECT_GT(c * depth, 45.0);
  // one mode, its stiffness -d(torque)/d(phi) of the torque about the pivot
  //   -k (phi - phi_free) + c l cos(phi) depth - m g l/2 cos(phi)
  const double stiffness = k + c * l * l * std::cos(phi) * std::cos(phi) + c * l * std::sin(phi) * depth -
                           m * g * l / 2 * std::sin(phi);
  const double inertia = m * l * l / 3;
  const std::vector<Mode> modes = eq.Linearise();
  ASSERT_EQ(modes.size(), 1u);
  EXPECT_NEAR(modes[0].natural_frequency_hz, std::sqrt(stiffness / inertia) / (2 * kPi), 1e-3);
  EXPECT_GT(modes[0].natural_frequency_hz, 50.0);  // not the free lever's 7 Hz
}

// A mass on a vertical guide held by the guide's friction (sliding force F,
// static limit 1.2 F) through its stick spring c, d; started at rest, so stuck.
std::string HeldMass(double mass) {
  return "<diagram name=\"held\">\n<identifiers>\n<identifier name=\"mass\" value=\"" + std::to_string(mass) +
         "\"/>\n</identifiers>\n"
         "<mechanism name=\"m\">\n"
         "<body name=\"B\" mass=\"mass\" inertia=\"0.01 0.01 0.01\"/>\n"
         "<joint name=\"jz\" type=\"translational\" body1=\"Base0\" body2=\"B\" axis=\"0 0 1\"/>\n"
         "<joint_force name=\"f\" type=\"frictional\" dof=\"jz\" friction=\"20\" ratio=\"1.2\" c=\"1e4\" d=\"100\"/>\n"
         "<sensor name=\"force\" kind=\"element\" element=\"f\" quantity=\"force\"/>\n"
         "</mechanism>\n<solver t_end=\"3\" rtol=\"1e-9\" atol=\"1e-12\"/>\n"
         "<output interval=\"0.01\"><log signal=\"m.force\"/></output>\n</diagram>\n";
}

TEST(EquilibriumModesTest, MassHeldByAStuckFrictionElementSinksIntoItsStickSpring) {
  // 1 kg under gravity, held (9.81 N < 24 N): the transient sinks by
  // m g / c into the stick spring, the deflection following the travel.
  // Newton must keep that bond (deflection less travel) as the transient
  // does, not leave the mass where it was and deflect the spring alone.
  const LastRow transient = Transient(testing::LoadXml(HeldMass(1)));
  Equilibrium eq(testing::LoadXml(HeldMass(1)));
  eq.Find();
  ExpectSameState(eq.x, transient.state, 1e-6);
  EXPECT_NEAR(eq.x[0], -9.81e-4, 1e-9);  // by the balance m g = c delta, independently
  EXPECT_EQ(eq.ctx.discrete, transient.discrete);
  EXPECT_EQ(eq.ctx.discrete, std::vector<double>{0.0});  // stuck
  EXPECT_EQ(eq.result.rounds, 1);
  ASSERT_EQ(eq.Modes().size(), 1u);
  EXPECT_THAT(eq.Modes()[0], HasSubstr("m.f: stuck on its stick spring"));
  // the mass on the stick spring: sqrt(c / m)
  const std::vector<Mode> modes = eq.Linearise();
  bool found = false;
  for (const Mode& mode : modes) found |= std::abs(mode.natural_frequency_hz - 100 / (2 * kPi)) < 1e-4;
  EXPECT_TRUE(found);
}

TEST(EquilibriumModesTest, FrictionElementThatCannotHoldIsRefusedByName) {
  // 3 kg: 29.4 N beyond the static limit of 24 N. Stuck, Newton balances it
  // on the stick spring; at that state the element breaks away, and sliding
  // leaves no rest state: refused, naming the element.
  Equilibrium eq(testing::LoadXml(HeldMass(3)));
  try {
    eq.Find();
    FAIL() << "expected a SimulationError, found x = " << eq.x[0] << " with " << eq.Modes()[0];
  } catch (const SimulationError& e) {
    EXPECT_THAT(std::string(e.what()), HasSubstr("no static equilibrium found"));
    EXPECT_THAT(std::string(e.what()), HasSubstr("'m.f' (now sliding backward"));
  }
}

TEST(EquilibriumModesTest, ModesThatCycleAreRefusedByName) {
  // x' = -x - 2 sat(x): from x = 5 (saturated above) Newton finds -2, where
  // the saturation is below; there it finds +2, above again, and so on.
  Equilibrium eq(testing::LoadXml(
      "<diagram>\n<blocks>\n"
      "<block type=\"integrator\" name=\"x\" initial=\"5\"/>\n"
      "<block type=\"saturation\" name=\"sat\" lower=\"-1\" upper=\"1\"/>\n"
      "<block type=\"expression\" name=\"rate\" inputs=\"x s\" expr=\"-x - 2*s\"/>\n"
      "</blocks>\n<connections>\n"
      "<connect from=\"x.y\" to=\"sat.u\"/><connect from=\"x.y\" to=\"rate.x\"/>\n"
      "<connect from=\"sat.y\" to=\"rate.s\"/><connect from=\"rate.y\" to=\"x.u\"/>\n"
      "</connections>\n</diagram>\n"));
  try {
    eq.Find();
    FAIL() << "expected a SimulationError, found x = " << eq.x[0];
  } catch (const SimulationError& e) {
    EXPECT_THAT(std::string(e.what()), HasSubstr("no static equilibrium found: the modes of 'sat' do not settle"));
  }
}

}  // namespace
}  // namespace mechflow::analysis
