// The Newton systems of rate pairs (blocks/second_order_solver.h).
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

#include "blocks/evaluation.h"
#include "blocks/second_order_solver.h"
#include "blocks/sparsity.h"
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
// to the column's largest magnitude.
double WorstRelativeError(const blocks::Results& run, const blocks::Results& reference) {
  double worst = 0.0;
  for (int c = 1; c < run.num_columns(); ++c) {
    const std::vector<double> a = run.Column(c), r = reference.Column(c);
    double scale = 0.0, diff = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) {
      scale = std::max(scale, std::abs(r[i]));
      diff = std::max(diff, std::abs(a[i] - r[i]));
    }
    worst = std::max(worst, diff / (1.0 + scale));
  }
  return worst;
}

// The reduction changes the Newton matrix, not the equations: against a run
// at a 1e4 times tighter tolerance it is as accurate as the whole system.
void ExpectAsAccurate(const std::string& example) {
  SCOPED_TRACE(example);
  const diagrams::LoadedDiagram loaded =
      diagrams::LoadDiagram(std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/" + example);
  blocks::SolverOptions whole = loaded.solver;
  whole.second_order = false;
  whole.linear_solver = blocks::LinearSolverKind::kDense;
  blocks::SolverOptions reduced = whole, tight = whole;
  reduced.second_order = true;
  tight.rtol *= 1e-4;
  tight.atol *= 1e-4;
  blocks::Simulator a(*loaded.diagram, whole, loaded.logged), b(*loaded.diagram, reduced, loaded.logged),
      reference(*loaded.diagram, tight, loaded.logged);
  ASSERT_TRUE(a.Run().ok);
  ASSERT_TRUE(b.Run().ok);
  ASSERT_TRUE(reference.Run().ok);
  const int n = loaded.diagram->num_states();
  EXPECT_EQ(a.stats().newton_size, n);
  EXPECT_EQ(b.stats().newton_size, n - static_cast<int>(blocks::DiagramRatePairs(*loaded.diagram).size()));
  ASSERT_EQ(a.results().num_rows(), reference.results().num_rows());
  ASSERT_EQ(b.results().num_rows(), reference.results().num_rows());
  const double error_whole = WorstRelativeError(a.results(), reference.results());
  const double error_reduced = WorstRelativeError(b.results(), reference.results());
  EXPECT_LE(error_reduced, 3.0 * error_whole + 10.0 * whole.rtol)
      << "whole system " << error_whole << ", reduced " << error_reduced;
}

TEST(SecondOrderSolverTest, RunsAsAccurateAsTheWholeSystem) {
  // (not the chaotic pendulum chain, whose error grows without bound)
  for (const char* example : {"pendulum.xml", "four_bar.xml", "slider_crank.xml", "elast_friction.xml",
                              "tension_mechanism.xml", "gears.xml", "oscillations.xml"})
    ExpectAsAccurate(example);
}

}  // namespace
}  // namespace mechflow
