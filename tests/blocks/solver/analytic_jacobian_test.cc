// Analytic Jacobians (blocks/solver/analytic_jacobian.h, mech/sliding_jacobian.h).
//
// 1. The analytic Jacobian equals central difference quotients of the
//    right-hand side, entry by entry, to 1e-6 of its row's largest entry, at
//    three random states of: every example diagram that has one, the P3
//    chain with masses stuck, sliding forward and sliding back, and a
//    sliding mechanism with everything the derivatives cover (oblique
//    lines, a joint with two perpendicular translations, a time-driven
//    translation, spline and linear tables, joint forces, an elastic-friction
//    element stuck and sliding, a frictional element on a joint, an applied
//    force).
// 2. Diagrams without one say why: rotations, non-perpendicular stacked
//    translations, laws without derivatives, feedback, a second stateful block.
// 3. Runs: the analytic Jacobian takes no right-hand sides, agrees with a
//    difference-quotient run, and tightening rtol moves it towards a tight
//    reference (dense and sparse paths).
// 4. <solver jacobian>: analytic where there is none is refused with the
//    file:line and the reason; a bad value too.

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
#include "blocks/solver/analytic_jacobian.h"
#include "tests/blocks/block_test_util.h"
#include "tests/test_util.h"

namespace mechflow {
namespace {

using blocks::AnalyticJacobian;

// The right-hand side and the analytic Jacobian at states of one diagram,
// its modes settled at the initial state.
class Harness {
 public:
  Harness(const blocks::Diagram& d, int block)
      : d_(d), jacobian_(d, block), n_(d.num_states()), ctx_(blocks::testing::SettledContext(d, &x0_)) {}
  int n() const { return n_; }
  const std::vector<double>& initial() const { return x0_; }
  std::vector<double> Rhs(double t, std::vector<double> x) {
    std::vector<double> f(n_);
    ctx_.time = t;
    ctx_.x = x.data();
    ctx_.xdot = f.data();
    ++ctx_.evaluation;
    ctx_.derivatives_follow = true;
    blocks::EvaluateOutputs(d_, &ctx_);
    blocks::EvaluateDerivatives(d_, &ctx_);
    ctx_.derivatives_follow = false;
    return f;
  }
  // column-major n x n
  std::vector<double> Analytic(double t, std::vector<double> x) {
    ctx_.time = t;
    ctx_.x = x.data();
    ++ctx_.evaluation;
    blocks::EvaluateOutputs(d_, &ctx_);
    jacobian_.Evaluate(&ctx_);
    std::vector<double> j(static_cast<std::size_t>(n_) * n_);
    jacobian_.ToDense(n_, j.data());
    return j;
  }
  std::vector<double> Central(double t, const std::vector<double>& x) {
    std::vector<double> j(static_cast<std::size_t>(n_) * n_);
    for (int c = 0; c < n_; ++c) {
      const double h = 1e-6 * (1.0 + std::abs(x[c]));
      std::vector<double> up = x, down = x;
      up[c] += h;
      down[c] -= h;
      const std::vector<double> fu = Rhs(t, up), fd = Rhs(t, down);
      for (int r = 0; r < n_; ++r) j[static_cast<std::size_t>(c) * n_ + r] = (fu[r] - fd[r]) / (2.0 * h);
    }
    return j;
  }

 private:
  const blocks::Diagram& d_;
  AnalyticJacobian jacobian_;
  int n_;
  std::vector<double> x0_;  // before ctx_, which points into it
  blocks::Context ctx_;
};

// Compares at three random states near the initial one; returns the number
// of entries above roundoff.
int ExpectAnalyticEqualsQuotients(const blocks::Diagram& d, double scale) {
  std::string why;
  const int block = AnalyticJacobian::FindBlock(d, &why);
  EXPECT_GE(block, 0) << why;
  if (block < 0) return 0;
  Harness h(d, block);
  const int n = h.n();
  int nonzeros = 0;
  for (unsigned seed : {1u, 2u, 3u}) {
    std::mt19937 gen(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<double> x = h.initial();
    for (double& xi : x) xi += scale * u(gen);
    const double t = 0.05 * seed;
    const std::vector<double> a = h.Analytic(t, x), q = h.Central(t, x);
    for (int r = 0; r < n; ++r) {
      double row_max = 0.0;
      for (int c = 0; c < n; ++c) row_max = std::max(row_max, std::abs(q[static_cast<std::size_t>(c) * n + r]));
      for (int c = 0; c < n; ++c) {
        const std::size_t k = static_cast<std::size_t>(c) * n + r;
        if (std::abs(q[k]) > 1e-9 * (1.0 + row_max)) ++nonzeros;
        EXPECT_NEAR(a[k], q[k], 1e-6 * (1.0 + row_max)) << "d f[" << r << "] / d x[" << c << "], seed " << seed;
      }
    }
  }
  return nonzeros;
}

// Everything the sliding derivatives cover. B slides in x and y on one joint
// (perpendicular), C slides in z; the springs run obliquely, so their
// directions turn as the bodies move; L is driven in time.
const char* kSliding = R"xml(<diagram name="sliding">
  <mechanism name="m">
    <body name="A" mass="2" inertia="1 1 1"/>
    <body name="B" mass="1.5" inertia="1 1 1"/>
    <body name="C" mass="0.7" inertia="1 1 1"/>
    <body name="L" mass="1" inertia="1 1 1"/>
    <joint name="jA" type="translational" body1="Base0" body2="A" point1="0 0 0" axis="1 0 0" q0="0.1" v0="0"/>
    <joint name="jB" type="generalized" body1="Base0" body2="B">
      <et type="tc" axis="0 1 0" value="1"/>
      <et type="tv" axis="1 0 0" name="x" q0="0.3" v0="-0.2"/>
      <et type="tv" axis="0 1 0" name="y" q0="0.1" v0="0"/>
    </joint>
    <joint name="jC" type="translational" body1="Base0" body2="C" point1="1 1 1" axis="0 0 1" q0="0.2" v0="0"/>
    <joint name="jL" type="generalized" body1="Base0" body2="L">
      <et type="tc" axis="0 0 1" value="2"/>
      <et type="tt" axis="1 0 0" value="0.3*t"/>
    </joint>
    <force name="AB" type="linear" body1="A" point1="0.1 0 0.2" body2="B" point2="0 0.1 0" c="300" d="2" x0="0.8"/>
    <force name="BC" type="points" body1="B" body2="C" points="0 0; 0.5 -40; 1 -60; 2 -200"
           interpolation="spline" d="0.5"/>
    <force name="CL" type="linear" body1="C" body2="L" c="150" d="1"/>
    <force name="AL" type="points" body1="A" body2="L" points="0 0; 1 -80; 3 -100"/>
    <force name="grip" type="elastic_friction" body1="Base0" point1="0 0 0" body2="A" friction="3" ratio="1.2"
           c="2000" d="20"/>
    <force name="slip" type="elastic_friction" body1="Base0" point1="0 3 0" body2="B" friction="2" ratio="1.2"
           c="1000" d="5"/>
    <force name="rub" type="frictional" body1="Base0" point1="1 1 3" body2="C" friction="1" ratio="1.2"
           c="5000" d="30"/>
    <joint_force name="hold" dof="y" type="linear" c="50" d="0.3"/>
    <joint_force name="rubx" dof="x" type="frictional" friction="0.5" ratio="1.2" c="4000" d="20"/>
    <applied_force name="push" body="C" force="0 0 5*sin(3*t)"/>
  </mechanism>
</diagram>)xml";

TEST(AnalyticJacobianTest, EqualsQuotientsOnEveryExampleThatHasOne) {
  namespace fs = std::filesystem;
  int with = 0, without = 0;
  for (const auto& entry : fs::directory_iterator(std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples")) {
    if (entry.path().extension() != ".xml") continue;
    SCOPED_TRACE(entry.path().filename().string());
    const diagrams::LoadedDiagram loaded = diagrams::LoadDiagram(entry.path().string());
    std::string why;
    if (AnalyticJacobian::FindBlock(*loaded.diagram, &why) < 0) {
      EXPECT_FALSE(why.empty());
      ++without;
      continue;
    }
    EXPECT_GT(ExpectAnalyticEqualsQuotients(*loaded.diagram, 1e-3), 0);
    ++with;
  }
  EXPECT_GE(with, 1);
  EXPECT_GT(with + without, 20);
}

TEST(AnalyticJacobianTest, EqualsQuotientsOnChainStuckAndSliding) {
  const int n = 9;
  std::vector<double> x0(n), v0(n);
  for (int i = 0; i < n; ++i) {
    x0[i] = 0.01 * i;
    v0[i] = i % 3 == 0 ? 0.0 : i % 3 == 1 ? 0.3 : -0.2;  // stuck, SLIP+, SLIP-
  }
  bench::DiagramSettings settings;
  const diagrams::LoadedDiagram loaded =
      testing::LoadXml(bench::FrictionLineDiagram(bench::ChainLine(n), x0, v0, settings));
  EXPECT_GT(ExpectAnalyticEqualsQuotients(*loaded.diagram, 1e-3), 5 * n);
}

TEST(AnalyticJacobianTest, EqualsQuotientsOnEverythingItCovers) {
  const diagrams::LoadedDiagram loaded = testing::LoadXml(kSliding);
  // elastic friction stuck (grip: A at rest) and sliding (slip: B moves),
  // frictional stuck (rub: C at rest) and sliding back (rubx: jB.x < 0)
  const blocks::Diagram& d = *loaded.diagram;
  std::string why;
  ASSERT_GE(AnalyticJacobian::FindBlock(d, &why), 0) << why;
  EXPECT_GT(ExpectAnalyticEqualsQuotients(d, 1e-2), 40);
}

std::string WhyNot(const std::string& xml) {
  const diagrams::LoadedDiagram loaded = testing::LoadXml(xml);
  std::string why;
  EXPECT_LT(AnalyticJacobian::FindBlock(*loaded.diagram, &why), 0);
  return why;
}

TEST(AnalyticJacobianTest, SaysWhyNot) {
  const std::string head = R"xml(<diagram name="w"><mechanism name="m">
    <body name="A" mass="1" inertia="1 1 1"/>)xml";
  EXPECT_NE(WhyNot(head + R"xml(<joint name="jA" type="rotational" body1="Base0" body2="A" axis="1 0 0"/>
    </mechanism></diagram>)xml").find("joint 'jA' turns"), std::string::npos);
  EXPECT_NE(WhyNot(head + R"xml(<body name="B" mass="1" inertia="1 1 1"/>
    <joint name="jA" type="translational" body1="Base0" body2="A" axis="1 0 0"/>
    <joint name="jB" type="translational" body1="A" body2="B" axis="1 1 0"/>
    </mechanism></diagram>)xml").find("joint 'jB' slides along a direction not perpendicular"), std::string::npos);
  const std::string expression = WhyNot(head + R"xml(<joint name="jA" type="translational" body1="Base0"
    body2="A" axis="1 0 0"/>
    <force name="e" type="expression" body1="Base0" body2="A" expression="-x"/>
    </mechanism></diagram>)xml");
  EXPECT_NE(expression.find("element 'e' (test.xml:4) gives no derivatives"), std::string::npos) << expression;
  // the mechanism's position, through a gain, pushes it: feedback
  EXPECT_NE(WhyNot(R"xml(<diagram name="w"><identifiers><identifier name="u" value="0"/></identifiers>
    <mechanism name="m"><input name="u"/><body name="A" mass="1" inertia="1 1 1"/>
    <joint name="jA" type="translational" body1="Base0" body2="A" axis="1 0 0"/>
    <applied_force name="p" body="A" force="u 0 0"/><sensor name="x" kind="coordinate" dof="jA"/></mechanism>
    <blocks><block type="gain" name="k" k="-5"/></blocks>
    <connections><connect from="m.x" to="k.u"/><connect from="k.y" to="m.u"/></connections></diagram>)xml")
                .find("an input of 'm' reads its states"),
            std::string::npos);
  EXPECT_NE(WhyNot(head + R"xml(<joint name="jA" type="translational" body1="Base0" body2="A" axis="1 0 0"/>
    </mechanism><blocks><block type="constant" name="c" value="1"/><block type="integrator" name="i" initial="0"/>
    </blocks><connections><connect from="c.y" to="i.u"/></connections></diagram>)xml")
                .find("both have states"),
            std::string::npos);
}

// --- 3. runs --------------------------------------------------------------------

std::string ChainXml(int n, const std::string& solver_attributes, double rtol = 1e-6) {
  std::vector<double> zero(n, 0.0);
  bench::DiagramSettings settings;
  settings.num_outputs = 100;
  settings.rtol = rtol;
  settings.atol = 1e-2 * rtol;
  std::string xml = bench::FrictionLineDiagram(bench::ChainLine(n), zero, zero, settings);
  xml.insert(xml.find("<solver ") + 8, solver_attributes + " ");
  return xml;
}

double WorstDifference(const testing::XmlRun& a, const testing::XmlRun& b, int n) {
  double worst = 0.0;
  for (int i = 1; i <= n; ++i) {
    const std::vector<double> p = a.Column("m.x" + std::to_string(i)), q = b.Column("m.x" + std::to_string(i));
    EXPECT_EQ(p.size(), q.size());
    for (std::size_t k = 0; k < std::min(p.size(), q.size()); ++k) worst = std::max(worst, std::abs(p[k] - q[k]));
  }
  return worst;
}

TEST(AnalyticJacobianTest, RunsAgreeAndTighten) {
  for (const char* solver : {"dense", "sparse"}) {
    SCOPED_TRACE(solver);
    const int n = 12;
    const std::string kind = std::string("linear_solver=\"") + solver + "\" ";
    const testing::XmlRun reference =
        testing::RunXml(ChainXml(n, kind + "jacobian=\"difference\"", 1e-11));
    const testing::XmlRun quotients = testing::RunXml(ChainXml(n, kind + "jacobian=\"difference\""));
    const testing::XmlRun analytic = testing::RunXml(ChainXml(n, kind + "jacobian=\"analytic\""));
    const testing::XmlRun tighter = testing::RunXml(ChainXml(n, kind + "jacobian=\"analytic\"", 1e-9));
    for (const testing::XmlRun* run : {&reference, &quotients, &analytic, &tighter}) ASSERT_TRUE(run->outcome.ok);
    EXPECT_TRUE(analytic.sim->stats().analytic_jacobian);
    EXPECT_FALSE(quotients.sim->stats().analytic_jacobian);
    EXPECT_EQ(analytic.sim->stats().sparse, std::string(solver) == "sparse");
    EXPECT_GT(analytic.sim->stats().jac_evals, 0);
    EXPECT_EQ(analytic.sim->stats().jac_rhs_evals, 0);  // every Jacobian where a right-hand side had just been
    EXPECT_GT(quotients.sim->stats().jac_rhs_evals, 0);
    // the same accuracy as difference quotients at rtol 1e-6 (motion about 5 mm) ...
    const double err_analytic = WorstDifference(analytic, reference, n);
    const double err_quotients = WorstDifference(quotients, reference, n);
    EXPECT_LT(err_analytic, 1e-6);
    EXPECT_LT(err_analytic, 3.0 * err_quotients + 1e-9);
    // ... and tightening gives a better answer
    EXPECT_LT(WorstDifference(tighter, reference, n), 0.1 * err_analytic);
  }
}

// --- 4. the setting --------------------------------------------------------------

TEST(AnalyticJacobianTest, SettingRefusedWhereThereIsNone) {
  const std::string pendulum = R"xml(<diagram name="p"><mechanism name="m">
    <body name="A" mass="1" com="0 0.5 0" inertia="1 1 1"/>
    <joint name="jA" type="rotational" body1="Base0" body2="A" axis="1 0 0" q0="0.5"/></mechanism>
    <solver t_end="1" jacobian="analytic"/></diagram>)xml";
  const std::string message = testing::InputErrorOf([&] { testing::LoadXml(pendulum); });
  EXPECT_NE(message.find("test.xml:4: solver jacobian=\"analytic\""), std::string::npos) << message;
  EXPECT_NE(message.find("joint 'jA' turns"), std::string::npos) << message;
  EXPECT_NE(message.find("use jacobian=\"auto\" or \"difference\""), std::string::npos) << message;
  std::string bad = pendulum;
  bad.replace(bad.find("analytic"), 8, "exact");
  EXPECT_NE(testing::InputErrorOf([&] { testing::LoadXml(bad); }).find("expected auto, analytic or difference"),
            std::string::npos);
  const std::string krylov = ChainXml(3, "linear_solver=\"krylov\" jacobian=\"analytic\"");
  EXPECT_NE(testing::InputErrorOf([&] { testing::LoadXml(krylov); }).find("krylov linear solver uses no Jacobian"),
            std::string::npos);
}

}  // namespace
}  // namespace mechflow
