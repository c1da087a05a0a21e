// The P1-P3 reference (bench/friction_direct.h) checked on its own: the free
// slide FR-1 against its closed form, the closed-form Coulomb stick-slip
// period against the CT-4 figures of docs/ELEMENTS.md and against the
// direct program with an ever stiffer stick, the chain without friction
// against its energy balance and the harmonic closed form, the banded
// analytic Jacobian against the dense difference-quotient one; and the
// generated diagrams (bench/friction_diagram.h) run by mechflow against the
// direct program.

#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bench/friction_diagram.h"
#include "bench/friction_direct.h"
#include "blocks/solver/simulator.h"
#include "diagrams/loader.h"
#include "diagrams/xml_reader.h"

namespace mb = mechflow::bench;

namespace {

constexpr double kPi = 3.14159265358979323846;

mb::FrictionRunOptions Tight(double t_end, mb::LinearSolver solver = mb::LinearSolver::kDenseDifferenceQuotient) {
  mb::FrictionRunOptions o;
  o.rtol = 1e-10, o.atol = 1e-12, o.t_end = t_end, o.solver = solver;
  return o;
}

std::vector<double> Breaks(const mb::FrictionRunResult& r) {
  std::vector<double> t;
  for (const auto& e : r.events)
    if (e.mass == 0 && e.crossing == 2) t.push_back(e.time);
  return t;
}

TEST(FrictionReference, FreeSlideStopsAtTheClosedFormAndStays) {
  // FR-1: m 10, v0 1.5, F 10 -> 1 m/s^2, stop at 1.5 s after 1.125 m
  const mb::SlideStop exact = mb::FreeSlideStop(10.0, 1.5, 10.0);
  EXPECT_DOUBLE_EQ(exact.time, 1.5);
  EXPECT_DOUBLE_EQ(exact.distance, 1.125);
  const mb::FrictionRunResult r = mb::RunFrictionLine(mb::FreeSlideLine(), {0.0}, {1.5}, Tight(2.0));
  ASSERT_EQ(r.events.size(), 1u);  // one stop, no break-away after it
  EXPECT_EQ(r.events[0].crossing, 0);
  EXPECT_NEAR(r.events[0].time, 1.5, 1e-9);
  EXPECT_NEAR(r.anchors[0], 1.125, 1e-9);
  EXPECT_EQ(r.modes[0], 0.0);
  EXPECT_LT(std::abs(r.x[0] - r.anchors[0]), 1e-12);  // creep after the stop
  EXPECT_LT(std::abs(r.v[0]), 1e-9);
}

// The rows the benchmark's direct program keeps: t, then per mass x, v, the
// friction force and mode, at t = 0 and every output time.
TEST(FrictionReference, FreeSlideRowsFollowTheClosedForm) {
  mb::FrictionRunOptions o = Tight(2.0);
  o.num_outputs = 20;
  o.rows = mb::FrictionRunOptions::Rows::kStatesAndFriction;
  const mb::FrictionRunResult r = mb::RunFrictionLine(mb::FreeSlideLine(), {0.0}, {1.5}, o);
  ASSERT_EQ(r.row_width, 5);
  ASSERT_EQ(r.rows.size(), 21u * 5u);
  for (int k = 0; k <= 20; ++k) {
    const double* row = &r.rows[5 * k];
    const double t = 0.1 * k;
    EXPECT_NEAR(row[0], t, 1e-12);
    const bool sliding = t < 1.5 - 1e-9;  // a = -1 m/s^2 until the stop at 1.5 s
    EXPECT_NEAR(row[1], sliding ? 1.5 * t - 0.5 * t * t : 1.125, 1e-8) << t;
    EXPECT_NEAR(row[2], sliding ? 1.5 - t : 0.0, 1e-8) << t;
    if (k == 15) continue;  // the stop's instant: either mode
    EXPECT_NEAR(row[3], sliding ? -10.0 : 0.0, 1e-6) << t;  // stuck at rest: no holding force
    EXPECT_EQ(row[4], sliding ? 1.0 : 0.0) << t;
  }
  EXPECT_EQ(r.rows[5 * 20 + 1], r.x[0]);
  o.rows = mb::FrictionRunOptions::Rows::kStates;
  EXPECT_EQ(mb::RunFrictionLine(mb::FreeSlideLine(), {0.0}, {1.5}, o).rows.size(), 21u * 3u);
}

TEST(FrictionReference, CoulombStickSlipMatchesTheCt4Figures) {
  // ELEMENTS.md CT-4, mu_s 0.4, mu_k 0.3: stick 0.1962 s + slip 0.4732 s = 0.6694 s (four digits)
  const mb::StickSlipCycle c = mb::CoulombStickSlip(1.0, 100.0, 0.1, 0.4, 0.3, 9.81);
  EXPECT_NEAR(c.stick, 0.1962, 5e-5);
  EXPECT_NEAR(c.slip, 0.4732, 5e-5);
  EXPECT_NEAR(c.period(), 0.6694, 5e-5);
  // equal coefficients: no stick, the slip arc is a whole period 2 pi sqrt(m/k)
  const mb::StickSlipCycle equal = mb::CoulombStickSlip(1.0, 100.0, 0.1, 0.3, 0.3, 9.81);
  EXPECT_DOUBLE_EQ(equal.stick, 0.0);
  EXPECT_NEAR(equal.slip, 2.0 * kPi / 10.0, 1e-15);
}

TEST(FrictionReference, StickSlipPeriodTendsToTheCoulombPeriodAsTheStickStiffens) {
  // P2: mu_s 0.6, mu_d 0.4. The elastic stick lengthens the stick phase by
  // about k/c_stick (the body yields while the spring loads), so the error
  // shrinks with the stick stiffness.
  const mb::StickSlipCycle exact = mb::CoulombStickSlip(1.0, 100.0, 0.1, 0.6, 0.4, 9.81);
  EXPECT_NEAR(exact.period(), 0.8008, 1e-4);  // README's piecewise Coulomb analysis of stick_slip_blocks.xml
  double last_error = 1.0;
  for (const double hz : {50.0, 500.0}) {
    const mb::FrictionLine line = mb::StickSlipLine(hz);
    const mb::FrictionRunResult r = mb::RunFrictionLine(line, {0.0}, {0.0}, Tight(10.0));
    const std::vector<double> b = Breaks(r);
    ASSERT_GE(b.size(), 10u) << hz;
    // first break-away when the spring reaches mu_s m g: t = mu_s m g/(k V)
    EXPECT_NEAR(b[0], 0.6 * 9.81 / 10.0, 2.0 * 100.0 / line.friction.stiffness * b[0]) << hz;
    const double period = (b.back() - b.front()) / (b.size() - 1);
    const double error = std::abs(period / exact.period() - 1.0);
    EXPECT_LT(error, 2.0 * 100.0 / line.friction.stiffness) << hz;
    EXPECT_LT(error, last_error) << hz;
    last_error = error;
    for (std::size_t i = 1; i < b.size(); ++i) EXPECT_NEAR(b[i] - b[i - 1], period, 1e-6) << hz << " cycle " << i;
  }
}

TEST(FrictionReference, ChainWithoutFrictionKeepsItsEnergyBalance) {
  mb::FrictionLine line = mb::ChainLine(5);
  line.friction = {};  // F = c = d = 0: the elements are inactive
  mb::FrictionRunOptions o = Tight(1.0);
  o.energy_states = true;
  const std::vector<double> x0{0.001, -0.002, 0.0, 0.003, 0.0}, v0{0.0, 0.1, 0.0, -0.2, 0.0};
  const mb::FrictionRunResult r = mb::RunFrictionLine(line, x0, v0, o);
  std::vector<double> y0, y1;
  for (int i = 0; i < 5; ++i) y0.insert(y0.end(), {x0[i], v0[i]}), y1.insert(y1.end(), {r.x[i], r.v[i]});
  const double e0 = line.MechanicalEnergy(0.0, y0.data()), e1 = line.MechanicalEnergy(1.0, y1.data());
  EXPECT_GT(std::abs(r.work), 1.0);       // the force does work
  EXPECT_GT(r.dissipated, 0.1);            // the dampers take some
  EXPECT_NEAR(e1 + r.dissipated - r.work, e0, 1e-7 * std::abs(r.work));
}

TEST(FrictionReference, OneMassOnItsSpringIsHarmonic) {
  mb::FrictionLine line;
  line.masses = {2.0};
  line.anchor_stiffness = 800.0;  // omega = 20 rad/s
  const mb::FrictionRunResult r = mb::RunFrictionLine(line, {0.01}, {0.0}, Tight(1.0));
  EXPECT_NEAR(r.x[0], 0.01 * std::cos(20.0), 1e-9);
  EXPECT_NEAR(r.v[0], -0.2 * std::sin(20.0), 5e-8);  // global error over 3.2 periods at rtol 1e-10
}

TEST(FrictionReference, BandedAnalyticJacobianGivesTheDenseResult) {
  const mb::FrictionLine line = mb::ChainLine(20);
  const std::vector<double> zero(20, 0.0);
  const mb::FrictionRunResult dense = mb::RunFrictionLine(line, zero, zero, Tight(0.3));
  mb::FrictionRunOptions band = Tight(0.3, mb::LinearSolver::kBandAnalytic);
  band.flush_subnormals = true;
  const mb::FrictionRunResult banded = mb::RunFrictionLine(line, zero, zero, band);
  ASSERT_GT(dense.events.size(), 20u);
  EXPECT_EQ(dense.events.size(), banded.events.size());
  for (int i = 0; i < 20; ++i) {
    EXPECT_NEAR(dense.x[i], banded.x[i], 1e-8) << i;
    EXPECT_NEAR(dense.v[i], banded.v[i], 1e-6) << i;
  }
  EXPECT_EQ(banded.jac_rhs_evals, 0);  // the analytic Jacobian, no difference quotients
}

// The generated diagram, run by mechflow at the tight tolerances.
struct MechflowRun {
  std::vector<double> x, v;
  long events;
  std::vector<double> breaks;
};

MechflowRun RunDiagram(const mb::FrictionLine& line, double t_end) {
  const int n = line.size();
  const std::vector<double> zero(n, 0.0);
  mb::DiagramSettings s;
  s.t_end = t_end, s.rtol = 1e-10, s.atol = 1e-12;
  const auto loaded = mechflow::diagrams::LoadDiagramDescription(
      mechflow::diagrams::ReadDiagramText(mb::FrictionLineDiagram(line, zero, zero, s), "generated.xml"));
  mechflow::blocks::Simulator sim(*loaded.diagram, loaded.solver, loaded.logged);
  const auto outcome = sim.Run();
  EXPECT_TRUE(outcome.ok) << outcome.failure;
  MechflowRun r;
  const auto& res = sim.results();
  for (int i = 0; i < n; ++i) {
    r.x.push_back(res.at(res.num_rows() - 1, res.FindColumn("m.x" + std::to_string(i + 1))));
    r.v.push_back(res.at(res.num_rows() - 1, res.FindColumn("m.v" + std::to_string(i + 1))));
  }
  r.events = sim.stats().events;
  for (const auto& e : sim.events())
    if (e.crossing == 2) r.breaks.push_back(e.time);
  return r;
}

TEST(FrictionDiagram, StickSlipDiagramRunsTheDirectEquations) {
  const mb::FrictionLine line = mb::StickSlipLine();
  const MechflowRun m = RunDiagram(line, 3.0);
  const mb::FrictionRunResult d = mb::RunFrictionLine(line, {0.0}, {0.0}, Tight(3.0));
  EXPECT_EQ(m.events, static_cast<long>(d.events.size()));
  const std::vector<double> b = Breaks(d);
  ASSERT_EQ(m.breaks.size(), b.size());
  ASSERT_GE(b.size(), 3u);
  for (std::size_t i = 0; i < b.size(); ++i) EXPECT_NEAR(m.breaks[i], b[i], 1e-8) << i;
  EXPECT_NEAR(m.x[0], d.x[0], 1e-8);
  EXPECT_NEAR(m.v[0], d.v[0], 1e-7);
}

TEST(FrictionDiagram, ChainDiagramRunsTheDirectEquations) {
  const mb::FrictionLine line = mb::ChainLine(4);
  const MechflowRun m = RunDiagram(line, 0.5);
  const std::vector<double> zero(4, 0.0);
  const mb::FrictionRunResult d = mb::RunFrictionLine(line, zero, zero, Tight(0.5));
  EXPECT_GT(d.events.size(), 10u);
  EXPECT_EQ(m.events, static_cast<long>(d.events.size()));
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(m.x[i], d.x[i], 1e-8) << i;
    EXPECT_NEAR(m.v[i], d.v[i], 1e-6) << i;
  }
}

}  // namespace
