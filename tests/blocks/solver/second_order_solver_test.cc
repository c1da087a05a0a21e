// The Newton systems of rate pairs (blocks/solver/second_order_solver.h).
//
// 1. The pairs a block declares hold: on every example diagram, at its
//    initial state and at a state with every velocity moved, each pair's
//    position derivative equals its rate state bit for bit.
// 2. The reduced solve is the whole system's solve: A x = b to round-off for
//    A = I - gamma J with random J (exact q' = v rows), with and without
//    states outside the pairs; a singular reduced matrix is refused as a
//    recoverable failure (CVODE then retries with a smaller step).
// 3. Runs are as accurate as the whole system's: on seven examples (loops,
//    element states beside the pairs, contact, gears) both runs are compared
//    with a run at a 1e4 times tighter tolerance; the counters say how many
//    unknowns each Newton system had.

#include <cmath>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "blocks/framework/evaluation.h"
#include "blocks/solver/second_order_solver.h"
#include "blocks/solver/sparsity.h"
#include "tests/test_util.h"

namespace mechflow {
namespace {

TEST(RatePairsTest, HoldExactlyOnEveryExample) {
  namespace fs = std::filesystem;
  int examples = 0, with_pairs = 0;
  for (const auto& entry : fs::directory_iterator(std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples")) {
    if (entry.path().extension() != ".xml") continue;
    SCOPED_TRACE(entry.path().filename().string());
    const diagrams::LoadedDiagram loaded = diagrams::LoadDiagram(entry.path().string());
    const blocks::Diagram& d = *loaded.diagram;
    const auto pairs = blocks::DiagramRatePairs(d);
    ++examples;
    if (pairs.empty()) continue;
    ++with_pairs;
    blocks::Context ctx;
    ctx.signals.assign(d.num_signals(), 0.0);
    ctx.discrete.assign(d.num_discrete_states(), 0.0);
    std::vector<double> x(d.num_states(), 0.0), f(d.num_states(), 0.0);
    ctx.x = x.data();
    ctx.xdot = f.data();
    blocks::InitializeStates(d, &ctx);
    blocks::SettleModes(d, &ctx);
    for (int moved = 0; moved < 2; ++moved) {
      if (moved)
        for (const auto& [position, rate] : pairs) x[rate] += 0.01 * (1 + rate % 3);
      ++ctx.evaluation;
      blocks::EvaluateOutputs(d, &ctx);
      blocks::EvaluateDerivatives(d, &ctx);
      for (const auto& [position, rate] : pairs) EXPECT_EQ(f[position], x[rate]) << "state " << position;
    }
  }
  EXPECT_GT(examples, 20);
  EXPECT_GT(with_pairs, 15);
}

// A = I - gamma J with J random except its exact rows q' = v.
struct NewtonSystem {
  NewtonSystem(int n, const std::vector<std::pair<int, int>>& pairs, double gamma, unsigned seed)
      : y(n, ctx), x(n, ctx), b(n, ctx), gamma(gamma) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> uniform(-1.0, 1.0);
    Eigen::MatrixXd j = Eigen::MatrixXd::NullaryExpr(n, n, [&] { return uniform(random); });
    for (const auto& [position, rate] : pairs) {
      j.row(position).setZero();
      j(position, rate) = 1.0;
    }
    a = Eigen::MatrixXd::Identity(n, n) - gamma * j;
    for (int i = 0; i < n; ++i) b.data()[i] = uniform(random);
  }
  blocks::sundials::Context ctx;
  blocks::sundials::Vector y, x, b;
  double gamma;
  Eigen::MatrixXd a;
};

void CopyInto(const Eigen::MatrixXd& a, SUNMatrix m) {
  double* values = SUNDenseMatrix_Data(m);
  for (Eigen::Index c = 0; c < a.cols(); ++c)
    for (Eigen::Index r = 0; r < a.rows(); ++r) values[c * a.rows() + r] = a(r, c);
}

TEST(SecondOrderSolverTest, SolvesTheWholeSystem) {
  // pairs not in state order, and states outside every pair
  const std::vector<std::pair<int, int>> pairs = {{0, 4}, {5, 1}, {2, 7}};
  for (const double gamma : {1e-4, 0.37, 3.0}) {
    NewtonSystem s(9, pairs, gamma, 7);
    blocks::SecondOrderSolver solver(s.y, pairs, [&] { return gamma; }, s.ctx);
    EXPECT_EQ(solver.reduced_size(), 6);
    CopyInto(s.a, solver.matrix());
    ASSERT_EQ(SUNLinSolSetup(solver.solver(), solver.matrix()), SUNLS_SUCCESS);
    ASSERT_EQ(SUNLinSolSolve(solver.solver(), solver.matrix(), s.x.get(), s.b.get(), 0.0), SUNLS_SUCCESS);
    const Eigen::Map<Eigen::VectorXd> x(s.x.data(), 9), b(s.b.data(), 9);
    EXPECT_LT((s.a * x - b).norm(), 1e-12 * (1.0 + b.norm())) << "gamma " << gamma;
  }
}

TEST(SecondOrderSolverTest, OnlyPairs) {
  const std::vector<std::pair<int, int>> pairs = {{0, 2}, {1, 3}};
  NewtonSystem s(4, pairs, 0.5, 11);
  blocks::SecondOrderSolver solver(s.y, pairs, [] { return 0.5; }, s.ctx);
  CopyInto(s.a, solver.matrix());
  ASSERT_EQ(SUNLinSolSetup(solver.solver(), solver.matrix()), SUNLS_SUCCESS);
  ASSERT_EQ(SUNLinSolSolve(solver.solver(), solver.matrix(), s.x.get(), s.b.get(), 0.0), SUNLS_SUCCESS);
  const Eigen::Map<Eigen::VectorXd> x(s.x.data(), 4), b(s.b.data(), 4);
  EXPECT_LT((s.a * x - b).norm(), 1e-13);
}

TEST(SecondOrderSolverTest, SingularReducedMatrixIsRecoverable) {
  const std::vector<std::pair<int, int>> pairs = {{0, 1}};
  NewtonSystem s(3, pairs, 0.5, 3);
  s.a.row(1) = s.a.row(2);  // rows R of the reduced matrix become equal too
  s.a(1, 0) = s.a(2, 0);
  blocks::SecondOrderSolver solver(s.y, pairs, [] { return 0.5; }, s.ctx);
  CopyInto(s.a, solver.matrix());
  EXPECT_GT(SUNLinSolSetup(solver.solver(), solver.matrix()), 0);
}

TEST(SecondOrderSolverTest, RefusesAPositionThatIsARate) {
  blocks::sundials::Context ctx;
  blocks::sundials::Vector y(4, ctx);
  EXPECT_THROW(blocks::SecondOrderSolver(y, {{0, 1}, {1, 2}}, [] { return 1.0; }, ctx), std::logic_error);
}

// Largest difference of each logged column from a reference run, relative
// to the column's largest magnitude. Rows within a microsecond of an event
// of either run are left out: an event at an output time may fall on either
// side of it (the box of ElastFriction stops at 1.5 s exactly).
double WorstRelativeError(const blocks::Simulator& run, const blocks::Simulator& reference) {
  const auto near_event = [&](double t) {
    for (const blocks::Simulator* s : {&run, &reference})
      for (const blocks::EventRecord& e : s->events())
        if (std::abs(e.time - t) < 1e-6) return true;
    return false;
  };
  const std::vector<double> time = reference.results().Column(0);
  double worst = 0.0;
  for (int c = 1; c < run.results().num_columns(); ++c) {
    const std::vector<double> a = run.results().Column(c), r = reference.results().Column(c);
    double scale = 0.0, diff = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) {
      scale = std::max(scale, std::abs(r[i]));
      if (!near_event(time[i])) diff = std::max(diff, std::abs(a[i] - r[i]));
    }
    worst = std::max(worst, diff / (1.0 + scale));
  }
  return worst;
}

// The reduction changes the Newton matrix, not the equations: against a run
// at a 1e4 times tighter tolerance it is as accurate as the whole system.
void ExpectAsAccurate(const std::string& example, blocks::LinearSolverKind kind = blocks::LinearSolverKind::kDense) {
  SCOPED_TRACE(example);
  const diagrams::LoadedDiagram loaded =
      diagrams::LoadDiagram(std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/" + example);
  blocks::SolverOptions whole = loaded.solver;
  whole.second_order = false;
  whole.linear_solver = blocks::LinearSolverKind::kDense;
  blocks::SolverOptions reduced = whole, tight = whole;
  reduced.second_order = true;
  reduced.linear_solver = kind;
  tight.rtol *= 1e-4;
  tight.atol *= 1e-4;
  blocks::Simulator a(*loaded.diagram, whole, loaded.logged), b(*loaded.diagram, reduced, loaded.logged),
      reference(*loaded.diagram, tight, loaded.logged);
  ASSERT_TRUE(a.Run().ok);
  ASSERT_TRUE(b.Run().ok);
  ASSERT_TRUE(reference.Run().ok);
  const int n = loaded.diagram->num_states();
  EXPECT_EQ(a.stats().newton_size, n);
  if (kind == blocks::LinearSolverKind::kDense) {
    EXPECT_EQ(b.stats().newton_size, n - static_cast<int>(blocks::DiagramRatePairs(*loaded.diagram).size()));
  }
  EXPECT_EQ(b.stats().krylov, kind == blocks::LinearSolverKind::kKrylov);
  ASSERT_EQ(a.results().num_rows(), reference.results().num_rows());
  ASSERT_EQ(b.results().num_rows(), reference.results().num_rows());
  const double error_whole = WorstRelativeError(a, reference);
  const double error_reduced = WorstRelativeError(b, reference);
  EXPECT_LE(error_reduced, 3.0 * error_whole + 10.0 * whole.rtol)
      << "whole system " << error_whole << ", reduced " << error_reduced;
}

TEST(SecondOrderSolverTest, RunsAsAccurateAsTheWholeSystem) {
  // (not the chaotic pendulum chain, whose error grows without bound)
  for (const char* example : {"pendulum.xml", "four_bar.xml", "slider_crank.xml", "elast_friction.xml",
                              "tension_mechanism.xml", "gears.xml", "oscillations.xml"})
    ExpectAsAccurate(example);
}

// GMRES preconditioned by the rows q' = v: the same accuracy on trees, with
// element states and events too. Not on closed loops: the slider-crank at
// its rtol 1e-8 is 5e-6 off against the dense solver's 3e-7 (its inexact
// solves and the projection onto the loops), so kAuto never picks it there.
TEST(KrylovSolverTest, RunsAsAccurateAsTheWholeSystem) {
  for (const char* example : {"pendulum.xml", "pendulum_chain.xml", "elast_friction.xml", "oscillations.xml"})
    ExpectAsAccurate(example, blocks::LinearSolverKind::kKrylov);
}

// A serial chain of n rods as XML (P4 of bench/README.md, shortened).
std::string Chain(int n, const std::string& solver_setting) {
  std::string x = "<diagram name=\"chain\"><mechanism name=\"c\">";
  for (int i = 1; i <= n; ++i)
    x += "<body name=\"R" + std::to_string(i) + "\" mass=\"1\" com=\"0 0.5 0\" inertia=\"1/12 1e-6 1/12\"/>";
  for (int i = 1; i <= n; ++i)
    x += "<joint name=\"j" + std::to_string(i) + "\" type=\"rotational\" body1=\"" +
         (i == 1 ? std::string("Base0") : "R" + std::to_string(i - 1)) + "\" body2=\"R" + std::to_string(i) + "\"" +
         (i == 1 ? "" : " point1=\"0 1 0\"") + " axis=\"1 0 0\"/>";
  x += "<sensor name=\"q1\" kind=\"coordinate\" dof=\"j1\"/></mechanism><solver t_end=\"0.2\" " + solver_setting +
       "/><output interval=\"0.01\"><log signal=\"c.q1\"/></output></diagram>";
  return x;
}

TEST(KrylovSolverTest, AutoPicksItForLargeDenseMechanisms) {
  const int n_min = blocks::Simulator::kKrylovMinStates / 2;  // bodies
  const testing::XmlRun small = testing::RunXml(Chain(n_min - 1, ""));
  const testing::XmlRun large = testing::RunXml(Chain(n_min, ""));
  const testing::XmlRun forced = testing::RunXml(Chain(3, "linear_solver=\"krylov\""));
  ASSERT_TRUE(small.outcome.ok && large.outcome.ok && forced.outcome.ok);
  EXPECT_FALSE(small.sim->stats().krylov);
  EXPECT_FALSE(small.sim->stats().sparse);
  EXPECT_EQ(small.sim->stats().newton_size, n_min - 1);  // the velocities only
  EXPECT_TRUE(large.sim->stats().krylov);
  EXPECT_GT(large.sim->stats().linear_iters, 0);
  EXPECT_EQ(large.sim->stats().jac_evals, 0);
  EXPECT_TRUE(forced.sim->stats().krylov);
  // the two sizes' first rods fall alike over 0.2 s (the chain below barely matters yet)
  EXPECT_NEAR(small.Column("c.q1").back(), large.Column("c.q1").back(), 1e-3);
}

}  // namespace
}  // namespace mechflow
