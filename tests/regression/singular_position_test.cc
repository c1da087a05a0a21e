// Singular positions (loops through dead centres must not stop the run): parallelogram four-bars pass, at
// every half turn, through the position where all links are collinear and
// the loops lose rank. Checked against the closed form of the coupled
// cranks: the parallelograms keep every crank at the same angle theta, so the
// mechanism is one pendulum-like body with
//   I = (N + 1) m_c a^2 / 3 + N m_r a^2,   V = g ((N + 1) m_c a / 2 + N m_r a) sin(theta)
// and I theta'^2 / 2 + V is constant.

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "blocks/library/mechanism_block.h"
#include "blocks/solver/simulator.h"
#include "diagrams/loader.h"
#include "mech/constraint_solve.h"
#include "mech/mechanism.h"
#include "tests/numbers.h"
#include "tests/test_util.h"

namespace mechflow::singular_position_test {  // names of its own: the files of its folder are compiled together
namespace {

using mechflow::testing::kPi;
constexpr double kG = 9.81, kA = 0.5, kD = 1.0;  // crank radius, rod length = pivot spacing

struct Energy {
  int rods;
  double Inertia() const { return (rods + 1) * kA * kA * kA / 3 + rods * kD * kA * kA; }
  double Potential(double theta) const {
    return kG * ((rods + 1) * kA * kA / 2 + rods * kD * kA) * std::sin(theta);
  }
  double Total(double theta, double rate) const { return Inertia() * rate * rate / 2 + Potential(theta); }
};

// N + 1 cranks on pivots kD apart joined by N rods (the coupling-rods example
// for N = 2), spun at w; gravity along -z.
std::string Ladder(int rods, double t_end, double rtol, double atol = 0.0) {
  std::ostringstream x;
  x << "<diagram name='ladder'><identifiers><identifier name='a' value='" << kA << "'/>"
    << "<identifier name='d' value='" << kD << "'/><identifier name='w' value='10'/></identifiers>"
    << "<mechanism name='m'>";
  for (int k = 0; k <= rods; ++k)
    x << "<body name='Crank" << k << "' mass='a' com='0 a/2 0' inertia='a^3/12 1e-4 a^3/12'/>";
  for (int k = 1; k <= rods; ++k)
    x << "<body name='Rod" << k << "' mass='d' com='0 d/2 0' inertia='d^3/12 1e-4 d^3/12'/>";
  for (int k = 0; k <= rods; ++k)
    x << "<joint name='p" << k << "' type='rotational' body1='Base0' body2='Crank" << k << "' point1='0 " << k
      << "*d 0' axis='1 0 0' q0='1' v0='w'/>";
  for (int k = 1; k <= rods; ++k) {
    x << "<joint name='a" << k << "' type='rotational' body1='Crank" << k - 1 << "' body2='Rod" << k
      << "' point1='0 a 0' axis='1 0 0' q0='-1' v0='-w'/>";
    x << "<joint name='b" << k << "' type='rotational' body1='Rod" << k << "' body2='Crank" << k
      << "' point1='0 d 0' point2='0 a 0' axis='1 0 0'/>";
  }
  x << "<sensor name='crank' kind='coordinate' dof='p0'/><sensor name='speed' kind='velocity' dof='p0'/>"
    << "<sensor name='last' kind='coordinate' dof='p" << rods << "'/></mechanism>"
    << "<solver t_end='" << t_end << "' rtol='" << rtol << "' atol='" << (atol > 0.0 ? atol : rtol * 1e-2) << "'/>"
    << "<output interval='0.01'><log signal='m.crank'/><log signal='m.speed'/><log signal='m.last'/></output>"
    << "</diagram>";
  return x.str();
}

// The largest change of the energy over the run, relative to it, and the
// largest angle between the first and the last crank.
struct Check {
  double energy_drift = 0.0, crank_spread = 0.0, turned = 0.0;
};
Check CheckRun(const testing::XmlRun& run, int rods) {
  const auto& r = run.sim->results();
  const auto theta = r.Column(r.FindColumn("m.crank")), rate = r.Column(r.FindColumn("m.speed")),
             last = r.Column(r.FindColumn("m.last"));
  const Energy energy{rods};
  const double e0 = energy.Total(theta[0], rate[0]);
  Check c;
  for (std::size_t i = 0; i < theta.size(); ++i) {
    c.energy_drift = std::max(c.energy_drift, std::abs(energy.Total(theta[i], rate[i]) - e0) / e0);
    c.crank_spread = std::max(c.crank_spread, std::abs(last[i] - theta[i]));
  }
  c.turned = theta.back() - theta.front();
  return c;
}

// atol 0: rtol / 100; t_end 0: the example's own (20 s)
testing::XmlRun RunExample(double rtol, double atol = 0.0, double t_end = 0.0) {
  diagrams::LoadedDiagram loaded =
      diagrams::LoadDiagram(std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/coupling_rods.xml");
  loaded.solver.rtol = rtol;
  loaded.solver.atol = atol > 0.0 ? atol : rtol * 1e-2;
  if (t_end > 0.0) loaded.solver.t_end = t_end;
  testing::XmlRun run{std::move(loaded), nullptr, {}};
  run.sim = std::make_unique<blocks::Simulator>(*run.loaded.diagram, run.loaded.solver, run.loaded.logged);
  run.outcome = run.sim->Run();
  return run;
}

TEST(SingularPositionTest, CouplingRodsPassTheirDeadCentres) {
  for (double rtol : {1e-6, 1e-7, 1e-8, 1e-9}) {
    const testing::XmlRun run = RunExample(rtol);
    ASSERT_TRUE(run.outcome.ok) << "rtol " << rtol << ": " << run.outcome.failure;
    const Check c = CheckRun(run, 2);
    // about 36 turns, 73 dead centres
    EXPECT_GT(c.turned, 36 * 2 * kPi) << "rtol " << rtol;
    EXPECT_LT(c.energy_drift, 2000 * rtol) << "rtol " << rtol;
    EXPECT_LT(c.crank_spread, 1e-6) << "rtol " << rtol;
  }
}

TEST(SingularPositionTest, TightTolerancesPassTheDeadCentresToo) {
  // Near a dead centre the loops determine the weak direction's position
  // only to eps L / sigma and its speed to eps L |J| |v| / sigma^2; when
  // the projections enforced it anyway, their round-off moved v by hundreds
  // of times the tolerance at every step, and these runs stopped there
  // (from t = 0.21 s at rtol 1e-12, atol 1e-13). Every one finishes now,
  // and the energy of the coupled cranks stays within 2000 times the
  // tolerance or 2e-8, the formulation's floor (measured over these 10 s:
  // 1.4e-9 .. 1.0e-7; 1.7e-8 at rtol 1e-11, atol 1e-10 before, over 20 s).
  // The cranks may part by a few
  // tolerances inside the band where the projections leave the weak
  // direction to the dynamics, and agree again after it.
  for (double rtol : {1e-10, 1e-11, 1e-12}) {
    for (double atol : {1e-10, 1e-11, 1e-12, 1e-13}) {
      const testing::XmlRun run = RunExample(rtol, atol, 10.0);
      EXPECT_TRUE(run.outcome.ok) << "rtol " << rtol << ", atol " << atol << ": " << run.outcome.failure;
      const Check c = CheckRun(run, 2);
      EXPECT_GT(c.turned, 17 * 2 * kPi) << "rtol " << rtol << ", atol " << atol;
      EXPECT_LT(c.energy_drift, std::max(2000 * std::max(rtol, atol), 2e-8)) << "rtol " << rtol << ", atol " << atol;
      EXPECT_LT(c.crank_spread, 1e-9) << "rtol " << rtol << ", atol " << atol;
    }
  }
}

TEST(SingularPositionTest, SpeedsFollowTheEnergyOfTheCoupledCranks) {
  const testing::XmlRun run = RunExample(1e-9);
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto& r = run.sim->results();
  const auto rate = r.Column(r.FindColumn("m.speed"));
  // the initial speed is kept as given (the loops take up the difference in
  // their own joints' rates), and the extremes are those of the closed form
  EXPECT_NEAR(rate[0], 10.0, 1e-12);
  const Energy e{2};
  const double e0 = e.Total(1.0, 10.0);
  const double fastest = std::sqrt(2 * (e0 - e.Potential(-kPi / 2)) / e.Inertia());
  const double slowest = std::sqrt(2 * (e0 - e.Potential(kPi / 2)) / e.Inertia());
  EXPECT_NEAR(*std::max_element(rate.begin(), rate.end()), fastest, 1e-4);  // on the 0.01 s grid
  EXPECT_NEAR(*std::min_element(rate.begin(), rate.end()), slowest, 1e-4);
}

TEST(SingularPositionTest, FortyParallelogramsPassTheirDeadCentres) {
  // the whole run (20 s) is a bench figure (bench/README.md); one second
  // passes the common dead centre three times
  const testing::XmlRun run = testing::RunXml(Ladder(40, 1.0, 1e-9));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const Check c = CheckRun(run, 40);
  EXPECT_GT(c.turned, 3 * kPi);
  EXPECT_LT(c.energy_drift, 1e-6);
  EXPECT_LT(c.crank_spread, 1e-7);
}

TEST(SingularPositionTest, FortyParallelogramsPassTheirFirstDeadCentreAtATightTolerance) {
  // 40 loops lose rank at once at t = 0.209 s; at rtol 1e-11, atol 1e-12
  // that stopped the run before the projections became tolerance-aware
  const testing::XmlRun run = testing::RunXml(Ladder(40, 0.3, 1e-11, 1e-12));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const Check c = CheckRun(run, 40);
  EXPECT_GT(c.turned, kPi);
  EXPECT_LT(c.energy_drift, 1e-8);
  EXPECT_LT(c.crank_spread, 1e-9);
}

TEST(SingularPositionTest, TheCollinearPositionIsNamed) {
  const testing::XmlRun run = testing::RunXml(Ladder(2, 0.1, 1e-8));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const auto& block = dynamic_cast<const blocks::MechanismBlock&>(
      run.loaded.diagram->block(run.loaded.diagram->FindBlock("m")));
  const mech::Mechanism& mechanism = block.mechanism();
  mech::MechanismWorkspace ws(mechanism);
  std::vector<double> x(mechanism.num_states()), modes(mechanism.num_modes());
  mech::InitialState(mechanism, {}, x, modes, &ws);
  const mech::Model& model = mechanism.model();
  std::span<double> q(x.data(), model.nq()), v(x.data() + model.nq(), model.nv());
  EXPECT_EQ(mech::SingularPositionNote(model, mechanism.constraints(), ws.constraint), "") << "at the start";
  // every crank and rod along the line of the pivots
  for (double& qi : q) qi = 0.0;
  mech::ProjectVelocities(model, mechanism.constraints(), 0.0, q, v, &ws.kin, &ws.constraint);
  const std::string note = mech::SingularPositionNote(model, mechanism.constraints(), ws.constraint);
  EXPECT_NE(note.find("the loops are at a singular position"), std::string::npos) << note;
  EXPECT_TRUE(note.find("joint 'b1'") != std::string::npos || note.find("joint 'b2'") != std::string::npos) << note;
  EXPECT_NE(note.find("rank 4 of 6"), std::string::npos) << note;
}

}  // namespace
}  // namespace mechflow::singular_position_test
