// Sparse Jacobians (blocks/solver/sparsity.h, blocks/solver/coloured_jacobian.h and the
// simulator's KLU path).
//
// 1. The structural pattern is a superset of the true one: at random states
//    of several diagrams (a branched tree with a spring between two trees,
//    the P3 chain with friction, a closed loop beside a free body, block
//    diagrams with and without a mechanism in a feedback loop) every entry of
//    a dense difference-quotient Jacobian that is not roundoff lies in it.
//    Roundoff: |J_ij| <= 1e-6 (1 + max_k |J_ik|); a structurally independent
//    entry is computed by the same operations as without the perturbation,
//    so its quotient is exactly zero except where a shared factorisation (the
//    loop's KKT solve) mixes roundoff in.
// 2. The coloured fill equals the dense quotient taken with the same
//    increments, entry by entry.
// 3. Runs with the sparse and the dense Jacobian agree on the P3 chain.
// 4. Selection (auto / dense / sparse), the <solver linear_solver> setting
//    and the counters.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bench/friction_diagram.h"
#include "bench/friction_direct.h"
#include "blocks/framework/evaluation.h"
#include "blocks/solver/coloured_jacobian.h"
#include "blocks/solver/sparsity.h"
#include "tests/blocks/block_test_util.h"
#include "tests/test_util.h"

namespace mechflow::sparse_jacobian_test {  // names of its own: the files of its folder are compiled together
namespace {

using blocks::ColouredJacobian;
using blocks::SparsityPattern;

// The diagram's right-hand side, set up the way blocks::Simulator does it.
class DiagramRhs {
 public:
  explicit DiagramRhs(const blocks::Diagram& d)
      : d_(d), n_(std::max(1, d.num_states())), ctx_(blocks::testing::SettledContext(d, &x0_)) {}
  int n() const { return n_; }
  const std::vector<double>& initial() const { return x0_; }
  int operator()(double* x, double* f) {
    ctx_.x = x;
    ctx_.xdot = f;
    ++ctx_.evaluation;
    blocks::EvaluateOutputs(d_, &ctx_);
    blocks::EvaluateDerivatives(d_, &ctx_);
    return 0;
  }
  // Global index of state `name` of block `block`.
  int State(const std::string& block, const std::string& name) const {
    const int b = d_.FindBlock(block);
    for (int i = 0; i < d_.block(b).num_states(); ++i)
      if (d_.block(b).state_name(i) == name) return d_.layout(b).first_state + i;
    throw std::runtime_error("no state " + block + "." + name);
  }

 private:
  const blocks::Diagram& d_;
  int n_;
  std::vector<double> x0_;  // before ctx_, which points into it
  blocks::Context ctx_;
};

// Dense difference quotients with the given increments, column-major n x n,
// the arithmetic of ColouredJacobian::Fill (and of CVODE's dense quotient).
std::vector<double> DenseQuotient(DiagramRhs& rhs, std::vector<double> x, const std::vector<double>& f0,
                                  const std::vector<double>& increments) {
  const int n = rhs.n();
  std::vector<double> jac(static_cast<std::size_t>(n) * n), f(n);
  for (int j = 0; j < n; ++j) {
    const double saved = x[j];
    x[j] += increments[j];
    rhs(x.data(), f.data());
    x[j] = saved;
    const double inverse = 1.0 / increments[j];
    for (int i = 0; i < n; ++i) jac[static_cast<std::size_t>(j) * n + i] = inverse * f[i] - inverse * f0[i];
  }
  return jac;
}

// The initial state moved by a seeded random amount (relative and absolute).
std::vector<double> RandomState(const std::vector<double>& x0, unsigned seed, double scale) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> x = x0;
  for (double& xi : x) xi += scale * (u(gen) + 0.1 * xi * u(gen));
  return x;
}

std::vector<double> Increments(const std::vector<double>& x, const std::vector<double>& f) {
  const int n = static_cast<int>(x.size());
  std::vector<double> weights(n), increments(n);
  for (int i = 0; i < n; ++i) weights[i] = 1.0 / (1e-6 * std::abs(x[i]) + 1e-8);
  blocks::DifferenceIncrements(n, x.data(), f.data(), weights.data(), 1e-3, increments.data());
  return increments;
}

// Every entry of the dense quotient above roundoff is in the pattern, at
// three random states; returns how many entries were checked to be nonzero.
int ExpectPatternCovers(const blocks::Diagram& d, double scale) {
  DiagramRhs rhs(d);
  const SparsityPattern pattern = blocks::DiagramSparsity(d);
  const int n = rhs.n();
  EXPECT_EQ(pattern.n, n);
  int nonzeros = 0;
  for (unsigned seed : {1u, 2u, 3u}) {
    std::vector<double> x = RandomState(rhs.initial(), seed, scale), f0(n);
    rhs(x.data(), f0.data());
    const std::vector<double> jac = DenseQuotient(rhs, x, f0, Increments(x, f0));
    for (int i = 0; i < n; ++i) {
      double row_max = 0.0;
      for (int j = 0; j < n; ++j) row_max = std::max(row_max, std::abs(jac[static_cast<std::size_t>(j) * n + i]));
      for (int j = 0; j < n; ++j) {
        const double value = jac[static_cast<std::size_t>(j) * n + i];
        if (std::abs(value) <= 1e-6 * (1.0 + row_max)) continue;
        ++nonzeros;
        EXPECT_TRUE(pattern.Contains(i, j)) << "d f[" << i << "] / d x[" << j << "] = " << value
                                            << " is missing from the pattern (seed " << seed << ")";
      }
    }
  }
  return nonzeros;
}

// --- diagrams ---------------------------------------------------------------

// Tree 1: A on the ground, B and C on A (two branches). Tree 2: D sliding
// along z, joined to B by a spring. Tree 3: E sliding along y on its own
// spring to the ground.
const char* kTrees = R"(<diagram name="trees">
  <mechanism name="m">
    <body name="A" mass="1" com="0 0.5 0" inertia="0.1 0.1 0.1"/>
    <body name="B" mass="1" com="0 0.5 0" inertia="0.1 0.1 0.1"/>
    <body name="C" mass="2" com="0 0.3 0" inertia="0.1 0.2 0.1"/>
    <body name="D" mass="1" inertia="0.1 0.1 0.1"/>
    <body name="E" mass="1" inertia="0.1 0.1 0.1"/>
    <joint name="jA" type="rotational" body1="Base0" body2="A" axis="1 0 0" q0="0.3" v0="1"/>
    <joint name="jB" type="rotational" body1="A" body2="B" point1="0 1 0" axis="1 0 0" q0="0.2"/>
    <joint name="jC" type="rotational" body1="A" body2="C" point1="0 0.5 0" axis="0 0 1" q0="-0.4"/>
    <joint name="jD" type="translational" body1="Base0" body2="D" point1="0 2 -1" axis="0 0 1" q0="0.1"/>
    <joint name="jE" type="translational" body1="Base0" body2="E" point1="3 0 0" axis="0 1 0" q0="0.2"/>
    <force name="s" type="linear" body1="B" point1="0 1 0" body2="D" point2="0 0 0" c="100" d="1"/>
    <force name="sE" type="linear" body1="Base0" point1="3 -1 0" body2="E" point2="0 0 0" c="50" d="0.5"/>
  </mechanism>
</diagram>)";

// A four-bar loop and a free slider in the same mechanism.
const char* kLoop = R"(<diagram name="loop">
  <mechanism name="m">
    <body name="Crank" mass="0.3" com="0 0.15 0" inertia="0.00225 1e-5 0.00225"/>
    <body name="Coupler" mass="0.8" com="0 0.4 0" inertia="0.0427 1e-5 0.0427"/>
    <body name="Rocker" mass="0.6" com="0 0.3 0" inertia="0.018 1e-5 0.018"/>
    <body name="Slider" mass="1" inertia="0.1 0.1 0.1"/>
    <joint name="j1" type="rotational" body1="Base0" body2="Crank" axis="1 0 0" q0="1.2" v0="6"/>
    <joint name="j2" type="rotational" body1="Crank" body2="Coupler" point1="0 0.3 0" axis="1 0 0" q0="-1"/>
    <joint name="j3" type="rotational" body1="Base0" body2="Rocker" point1="0 0.7 0" axis="1 0 0" q0="1.9"/>
    <joint name="j4" type="rotational" body1="Coupler" body2="Rocker" point1="0 0.8 0" point2="0 0.6 0" axis="1 0 0"/>
    <joint name="jS" type="translational" body1="Base0" body2="Slider" point1="5 0 0" axis="0 0 1" q0="0.5"/>
    <force name="spring" type="linear" body1="Base0" point1="5 0 2" body2="Slider" point2="0 0 0" c="1000" d="2"/>
    <sensor name="rocker" kind="coordinate" dof="j3"/>
  </mechanism>
</diagram>)";

// Two sliders; the position of the first, through a gain and an integrator,
// pushes the second (feedthrough chain and a block state in the loop).
const char* kFeedback = R"(<diagram name="feedback">
  <identifiers><identifier name="u" value="0"/></identifiers>
  <mechanism name="m">
    <input name="u"/>
    <body name="M1" mass="1" inertia="1 1 1"/>
    <body name="M2" mass="2" inertia="1 1 1"/>
    <joint name="j1" type="translational" body1="Base0" body2="M1" point1="1 0 0" axis="1 0 0" q0="0.1" v0="0.5"/>
    <joint name="j2" type="translational" body1="Base0" body2="M2" point1="0 1 0" axis="0 1 0" q0="0.2"/>
    <force name="s1" type="linear" body1="Base0" point1="0 0 0" body2="M1" c="400" d="1"/>
    <force name="s2" type="linear" body1="Base0" point1="0 0 0" body2="M2" c="300" d="1"/>
    <applied_force name="push" body="M2" force="0 u 0"/>
    <sensor name="x1" kind="coordinate" dof="j1"/>
  </mechanism>
  <blocks>
    <block type="gain" name="k" k="-50"/>
    <block type="integrator" name="i" initial="0"/>
    <block type="sum" name="add" signs="++"/>
  </blocks>
  <connections>
    <connect from="m.x1" to="k.u"/>
    <connect from="m.x1" to="i.u"/>
    <connect from="k.y" to="add.u1"/>
    <connect from="i.y" to="add.u2"/>
    <connect from="add.y" to="m.u"/>
  </connections>
</diagram>)";

std::string ChainXml(int n, const std::string& solver_attributes = "") {
  bench::DiagramSettings settings;
  settings.num_outputs = 100;
  std::string xml = bench::FrictionLineDiagram(bench::ChainLine(n), std::vector<double>(n, 0.0),
                                               std::vector<double>(n, 0.0), settings);
  if (!solver_attributes.empty()) {
    const std::size_t at = xml.find("<solver ");
    xml.insert(at + 8, solver_attributes + " ");
  }
  return xml;
}

// --- 1. the pattern covers the Jacobian --------------------------------------

TEST(SparsityPatternTest, TreesCoupleOnlyThroughElements) {
  const diagrams::LoadedDiagram loaded = testing::LoadXml(kTrees);
  const blocks::Diagram& d = *loaded.diagram;
  EXPECT_GT(ExpectPatternCovers(d, 0.3), 20);
  const SparsityPattern p = blocks::DiagramSparsity(d);
  const DiagramRhs rhs(d);
  const int vE = rhs.State("m", "v:jE"), qE = rhs.State("m", "q:jE");
  // the spring joins D to the branch B: D's acceleration reads the whole tree
  EXPECT_TRUE(p.Contains(rhs.State("m", "v:jD"), rhs.State("m", "q:jC")));
  EXPECT_TRUE(p.Contains(rhs.State("m", "v:jC"), rhs.State("m", "q:jD")));
  // E is alone
  for (const char* other : {"q:jA", "q:jB", "q:jC", "q:jD", "v:jA", "v:jD"}) {
    EXPECT_FALSE(p.Contains(vE, rhs.State("m", other))) << other;
    EXPECT_FALSE(p.Contains(rhs.State("m", other), qE)) << other;
  }
  // q' reads its own v only
  EXPECT_TRUE(p.Contains(qE, vE));
  EXPECT_FALSE(p.Contains(qE, rhs.State("m", "v:jA")));
}

// Every example diagram: whatever its elements, blocks and loops, no entry of
// the Jacobian falls outside the pattern (an element that forgot to declare
// its footprint would show here).
TEST(SparsityPatternTest, CoversEveryExample) {
  namespace fs = std::filesystem;
  int examples = 0;
  for (const auto& entry : fs::directory_iterator(std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples")) {
    if (entry.path().extension() != ".xml") continue;
    SCOPED_TRACE(entry.path().filename().string());
    const diagrams::LoadedDiagram loaded = diagrams::LoadDiagram(entry.path().string());
    ExpectPatternCovers(*loaded.diagram, 1e-3);
    ++examples;
  }
  EXPECT_GT(examples, 20);
}

TEST(SparsityPatternTest, FrictionChainIsBanded) {
  const int n = 6;
  const diagrams::LoadedDiagram loaded = testing::LoadXml(ChainXml(n));
  const blocks::Diagram& d = *loaded.diagram;
  EXPECT_GT(ExpectPatternCovers(d, 1e-3), 3 * n);
  // each acceleration reads its own and its neighbours' coordinates and the
  // stick deflections of the two elements at its body; each deflection reads
  // the rates of its element's two bodies; the q' rows read v
  const SparsityPattern p = blocks::DiagramSparsity(d);
  EXPECT_LE(p.nonzeros(), 2 * n + 6 * n + n + 2 * n + 2 * n);
  int colours = 0;
  blocks::ColourColumns(p, &colours);
  EXPECT_LE(colours, 7);
}

TEST(SparsityPatternTest, ClosedLoopIsCoupledAndTheFreeSliderIsNot) {
  const diagrams::LoadedDiagram loaded = testing::LoadXml(kLoop);
  const blocks::Diagram& d = *loaded.diagram;
  EXPECT_GT(ExpectPatternCovers(d, 0.05), 10);
  const SparsityPattern p = blocks::DiagramSparsity(d);
  const DiagramRhs rhs(d);
  // the loop joins the crank's tree and the rocker's
  EXPECT_TRUE(p.Contains(rhs.State("m", "v:j3"), rhs.State("m", "q:j1")));
  EXPECT_TRUE(p.Contains(rhs.State("m", "v:j1"), rhs.State("m", "v:j3")));
  for (const char* loop : {"q:j1", "q:j2", "q:j3", "v:j1", "v:j2", "v:j3"}) {
    EXPECT_FALSE(p.Contains(rhs.State("m", "v:jS"), rhs.State("m", loop))) << loop;
    EXPECT_FALSE(p.Contains(rhs.State("m", loop), rhs.State("m", "q:jS"))) << loop;
  }
}

TEST(SparsityPatternTest, FeedbackThroughBlocks) {
  const diagrams::LoadedDiagram loaded = testing::LoadXml(kFeedback);
  const blocks::Diagram& d = *loaded.diagram;
  EXPECT_GT(ExpectPatternCovers(d, 0.05), 6);
  const SparsityPattern p = blocks::DiagramSparsity(d);
  const DiagramRhs rhs(d);
  const int q1 = rhs.State("m", "q:j1"), v1 = rhs.State("m", "v:j1"), q2 = rhs.State("m", "q:j2"),
            v2 = rhs.State("m", "v:j2"), i = d.layout(d.FindBlock("i")).first_state;
  EXPECT_TRUE(p.Contains(v2, q1));  // through the gain (feedthrough chain)
  EXPECT_TRUE(p.Contains(v2, i));   // through the integrator's output
  EXPECT_TRUE(p.Contains(i, q1));   // the integrator integrates x1
  EXPECT_FALSE(p.Contains(v1, q2));
  EXPECT_FALSE(p.Contains(v1, i));
  EXPECT_FALSE(p.Contains(i, q2));
}

TEST(SparsityPatternTest, PureBlockDiagram) {
  const diagrams::LoadedDiagram loaded =
      diagrams::LoadDiagram(std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/three_masses_blocks.xml");
  const blocks::Diagram& d = *loaded.diagram;
  EXPECT_GT(ExpectPatternCovers(d, 1e-3), 6);
  const SparsityPattern p = blocks::DiagramSparsity(d);
  const DiagramRhs rhs(d);
  // x1' = v1 reads nothing else; v1' reads x1 and x2, not x3
  const int x1 = rhs.State("x1", "x"), v1 = rhs.State("v1", "x"), x3 = rhs.State("x3", "x");
  EXPECT_TRUE(p.Contains(x1, v1));
  EXPECT_FALSE(p.Contains(x1, x3));
  EXPECT_FALSE(p.Contains(v1, x3));
}

// --- 2. the coloured fill equals the dense quotient ----------------------------

void ExpectColouredEqualsDense(const blocks::Diagram& d, double scale) {
  DiagramRhs rhs(d);
  ColouredJacobian jacobian(blocks::DiagramSparsity(d));
  const SparsityPattern& p = jacobian.pattern();
  const int n = rhs.n();
  EXPECT_LE(jacobian.num_colours(), n);
  for (unsigned seed : {4u, 5u}) {
    std::vector<double> x = RandomState(rhs.initial(), seed, scale), f0(n);
    rhs(x.data(), f0.data());
    const std::vector<double> increments = Increments(x, f0);
    const std::vector<double> dense = DenseQuotient(rhs, x, f0, increments);
    ASSERT_EQ(jacobian.Fill(x.data(), f0.data(), increments.data(), rhs), 0);
    for (int j = 0; j < n; ++j) {
      for (int k = p.column_start[j]; k < p.column_start[j + 1]; ++k) {
        const int i = p.rows[k];
        double row_max = 0.0;
        for (int c = 0; c < n; ++c) row_max = std::max(row_max, std::abs(dense[static_cast<std::size_t>(c) * n + i]));
        // the same increments and operations: equal up to the roundoff a
        // shared factorisation mixes in (see the file comment)
        EXPECT_NEAR(jacobian.values()[k], dense[static_cast<std::size_t>(j) * n + i], 1e-6 * (1.0 + row_max))
            << "entry (" << i << ", " << j << ")";
      }
    }
  }
}

TEST(ColouredJacobianTest, EqualsDenseQuotientOnTrees) {
  ExpectColouredEqualsDense(*testing::LoadXml(kTrees).diagram, 0.3);
}

TEST(ColouredJacobianTest, EqualsDenseQuotientOnFrictionChain) {
  const diagrams::LoadedDiagram loaded = testing::LoadXml(ChainXml(12));
  ExpectColouredEqualsDense(*loaded.diagram, 1e-3);
  int colours = 0;
  blocks::ColourColumns(blocks::DiagramSparsity(*loaded.diagram), &colours);
  EXPECT_LE(colours, 7);  // 36 states (q, v, stick deflection), banded
}

TEST(ColouredJacobianTest, EqualsDenseQuotientOnLoop) {
  ExpectColouredEqualsDense(*testing::LoadXml(kLoop).diagram, 0.05);
}

TEST(ColouredJacobianTest, EqualsDenseQuotientOnFeedback) {
  ExpectColouredEqualsDense(*testing::LoadXml(kFeedback).diagram, 0.05);
}

TEST(ColouredJacobianTest, ColouringSeparatesColumnsThatShareARow) {
  // arrow pattern: row 0 reads every column, so every column needs its own colour
  SparsityPattern p;
  p.n = 4;
  p.column_start = {0, 4, 6, 8, 10};
  p.rows = {0, 1, 2, 3, 0, 1, 0, 2, 0, 3};
  int colours = 0;
  const std::vector<int> c = blocks::ColourColumns(p, &colours);
  EXPECT_EQ(colours, 4);
  // tridiagonal: three colours, j mod 3
  SparsityPattern t;
  t.n = 7;
  t.column_start.push_back(0);
  for (int j = 0; j < t.n; ++j) {
    for (int i = std::max(0, j - 1); i <= std::min(t.n - 1, j + 1); ++i) t.rows.push_back(i);
    t.column_start.push_back(static_cast<int>(t.rows.size()));
  }
  const std::vector<int> ct = blocks::ColourColumns(t, &colours);
  EXPECT_EQ(colours, 3);
  for (int j = 0; j < t.n; ++j) EXPECT_EQ(ct[j], j % 3);
}

// --- 3. sparse and dense runs agree ------------------------------------------

TEST(SparseSolverTest, SparseAndDenseRunsAgreeOnFrictionChain) {
  const int n = 20;
  // difference quotients (the analytic Jacobian has its own tests)
  const testing::XmlRun dense = testing::RunXml(ChainXml(n, "linear_solver=\"dense\" jacobian=\"difference\""));
  const testing::XmlRun sparse = testing::RunXml(ChainXml(n, "linear_solver=\"sparse\" jacobian=\"difference\""));
  ASSERT_TRUE(dense.outcome.ok) << dense.outcome.failure;
  ASSERT_TRUE(sparse.outcome.ok) << sparse.outcome.failure;
  EXPECT_FALSE(dense.sim->stats().sparse);
  EXPECT_TRUE(sparse.sim->stats().sparse);
  EXPECT_GT(sparse.sim->stats().jac_evals, 0);
  // every fill costs one right-hand side per colour
  EXPECT_EQ(sparse.sim->stats().jac_rhs_evals, sparse.sim->stats().jac_evals * sparse.sim->stats().colours);
  // both integrate to rtol 1e-6, atol 1e-8; the largest motion is about 5 mm
  // (last mass), so 1e-6 m is a few local tolerances accumulated over the run
  double worst = 0.0;
  for (int i = 1; i <= n; ++i) {
    const std::vector<double> a = dense.Column("m.x" + std::to_string(i)),
                              b = sparse.Column("m.x" + std::to_string(i));
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t k = 0; k < a.size(); ++k) worst = std::max(worst, std::abs(a[k] - b[k]));
  }
  EXPECT_LT(worst, 1e-6);
  const std::vector<double> last = dense.Column("m.x" + std::to_string(n));
  EXPECT_GT(*std::max_element(last.begin(), last.end()), 1e-4);  // the chain does move
}

// --- 4. selection and settings -----------------------------------------------

TEST(SparseSolverTest, AutoPicksDenseForSmallAndSparseForLargeChains) {
  const diagrams::LoadedDiagram small = testing::LoadXml(ChainXml(6));  // 18 states
  const blocks::Simulator small_sim(*small.diagram, small.solver, small.logged);
  EXPECT_EQ(small_sim.sparse_jacobian(), nullptr);
  const diagrams::LoadedDiagram ten = testing::LoadXml(ChainXml(10));  // 30 states
  const blocks::Simulator ten_sim(*ten.diagram, ten.solver, ten.logged);
  EXPECT_NE(ten_sim.sparse_jacobian(), nullptr);
  const diagrams::LoadedDiagram large = testing::LoadXml(ChainXml(100));
  const blocks::Simulator large_sim(*large.diagram, large.solver, large.logged);
  ASSERT_NE(large_sim.sparse_jacobian(), nullptr);
  EXPECT_LE(large_sim.sparse_jacobian()->num_colours(), 7);
  EXPECT_EQ(large_sim.sparse_jacobian()->pattern().n, 300);  // q, v, stick deflection
}

TEST(SparseSolverTest, DenseSettingWinsOverAuto) {
  const diagrams::LoadedDiagram large = testing::LoadXml(ChainXml(100, "linear_solver=\"dense\""));
  EXPECT_EQ(large.solver.linear_solver, blocks::LinearSolverKind::kDense);
  const blocks::Simulator sim(*large.diagram, large.solver, large.logged);
  EXPECT_EQ(sim.sparse_jacobian(), nullptr);
}

TEST(SparseSolverTest, BadSettingNamesTheLine) {
  const std::string message = testing::InputErrorOf([] { testing::LoadXml(ChainXml(2, "linear_solver=\"banded\"")); });
  EXPECT_NE(message.find("test.xml:"), std::string::npos) << message;
  EXPECT_NE(message.find("solver setting 'linear_solver' is 'banded'; expected auto, dense, sparse or krylov"),
            std::string::npos)
      << message;
}

TEST(SparseSolverTest, SparseRunOfAStatelessDiagram) {
  const testing::XmlRun run = testing::RunXml(R"(<diagram name="t">
    <blocks><block type="sine" name="s" amplitude="1" frequency="1"/></blocks>
    <solver linear_solver="sparse"/>
  </diagram>)");
  EXPECT_TRUE(run.outcome.ok) << run.outcome.failure;
  EXPECT_TRUE(run.sim->stats().sparse);
}

}  // namespace
}  // namespace mechflow::sparse_jacobian_test
