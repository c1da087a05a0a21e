// Linear analysis (analysis/linearization.h): the finite-difference Jacobian
// against analytic matrices, the damped Newton equilibrium, and the modal
// analysis against closed forms and an independent generalized symmetric
// eigenproblem (K - w^2 M) phi = 0.

#include "analysis/linearization.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include "diagrams/loader.h"
#include "mech/errors.h"
#include "tests/numbers.h"
#include "tests/test_util.h"

namespace mechflow::analysis {
namespace {

using namespace blocks;

using mechflow::testing::kPi;

std::string Example(const std::string& name) {
  return std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/" + name;
}

// A loaded diagram with a context at its initial state.
struct Linearised {
  diagrams::LoadedDiagram loaded;
  Context ctx;
  std::vector<double> x;

  explicit Linearised(diagrams::LoadedDiagram d) : loaded(std::move(d)) {
    PrepareContext(*loaded.diagram, loaded.solver.t_start, &ctx, &x);
  }
  const Diagram& diagram() const { return *loaded.diagram; }
  Eigen::MatrixXd Jacobian() { return StateJacobian(diagram(), &ctx, x); }
  int State(const std::string& name) const {
    const auto names = StateNames(diagram());
    const auto it = std::find(names.begin(), names.end(), name);
    if (it == names.end()) throw std::logic_error("no state " + name);
    return static_cast<int>(it - names.begin());
  }
};

Linearised FromFile(const std::string& example, const diagrams::LoadOptions& options = {}) {
  return Linearised(diagrams::LoadDiagram(Example(example), options));
}

Linearised FromXml(const std::string& xml) { return Linearised(testing::LoadXml(xml)); }

// The state-space matrix of a diagram written in the order the states are
// declared (x1, x2, x3), each integrator fed by a sum of gains:
//   x1' = -2 x1 + 3 x2,  x2' = x3,  x3' = -50 x1 - 0.5 x3 + 4 x2
const char* kLinear =
    "<diagram>\n<blocks>\n"
    "<block type=\"integrator\" name=\"x1\" initial=\"1200\"/>\n"
    "<block type=\"integrator\" name=\"x2\" initial=\"-0.003\"/>\n"
    "<block type=\"integrator\" name=\"x3\" initial=\"7\"/>\n"
    "<block type=\"gain\" name=\"a11\" k=\"-2\"/>\n"
    "<block type=\"gain\" name=\"a12\" k=\"3\"/>\n"
    "<block type=\"gain\" name=\"a31\" k=\"-50\"/>\n"
    "<block type=\"gain\" name=\"a32\" k=\"4\"/>\n"
    "<block type=\"gain\" name=\"a33\" k=\"-0.5\"/>\n"
    "<block type=\"sum\" name=\"r1\" signs=\"++\"/>\n"
    "<block type=\"sum\" name=\"r3\" signs=\"+++\"/>\n"
    "</blocks>\n<connections>\n"
    "<connect from=\"x1.y\" to=\"a11.u\"/><connect from=\"x2.y\" to=\"a12.u\"/>\n"
    "<connect from=\"a11.y\" to=\"r1.u1\"/><connect from=\"a12.y\" to=\"r1.u2\"/>\n"
    "<connect from=\"r1.y\" to=\"x1.u\"/>\n"
    "<connect from=\"x3.y\" to=\"x2.u\"/>\n"
    "<connect from=\"x1.y\" to=\"a31.u\"/><connect from=\"x2.y\" to=\"a32.u\"/>\n"
    "<connect from=\"x3.y\" to=\"a33.u\"/>\n"
    "<connect from=\"a31.y\" to=\"r3.u1\"/><connect from=\"a32.y\" to=\"r3.u2\"/>\n"
    "<connect from=\"a33.y\" to=\"r3.u3\"/>\n"
    "<connect from=\"r3.y\" to=\"x3.u\"/>\n"
    "</connections>\n</diagram>\n";

TEST(LinearizationTest, JacobianOfALinearDiagramIsItsMatrix) {
  Linearised lin = FromXml(kLinear);
  Eigen::MatrixXd expected(3, 3);
  expected << -2, 3, 0, 0, 0, 1, -50, 4, -0.5;
  const Eigen::MatrixXd A = lin.Jacobian();
  // a linear right-hand side differences exactly up to rounding of the
  // probes (states of 1e3 and 1e-3 magnitude): 1e-6 relative is generous
  EXPECT_LE((A - expected).cwiseAbs().maxCoeff(), 1e-6 * expected.cwiseAbs().maxCoeff()) << A;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      EXPECT_NEAR(A(i, j), expected(i, j), 1e-6 * std::max(1.0, std::abs(expected(i, j)))) << i << "," << j;
  // the state is left as it was, and the context evaluated at it
  EXPECT_EQ(lin.x[0], 1200);
  EXPECT_EQ(lin.x[1], -0.003);
  EXPECT_EQ(lin.ctx.x, lin.x.data());
  EXPECT_EQ(lin.ctx.xdot, nullptr);
  EXPECT_EQ(lin.ctx.signals[lin.diagram().ResolveSignal("a11.y").offset], -2400);
}

TEST(LinearizationTest, JacobianOfANonlinearExpressionToCentralDifferenceAccuracy) {
  // x' = -x^3 + sin(v), v' = -x v: A = [[-3 x^2, cos v], [-v, -x]]. Central
  // differences with h = eps^(1/3) |x| err by about h^2 |f'''| / 6: ~1e-11 here.
  Linearised lin = FromXml(
      "<diagram>\n<blocks>\n"
      "<block type=\"integrator\" name=\"x\" initial=\"2.5\"/>\n"
      "<block type=\"integrator\" name=\"v\" initial=\"0.7\"/>\n"
      "<block type=\"expression\" name=\"fx\" inputs=\"x v\" expr=\"-x^3 + math.sin(v)\"/>\n"
      "<block type=\"expression\" name=\"fv\" inputs=\"x v\" expr=\"-x*v\"/>\n"
      "</blocks>\n<connections>\n"
      "<connect from=\"x.y\" to=\"fx.x\"/><connect from=\"v.y\" to=\"fx.v\"/>\n"
      "<connect from=\"x.y\" to=\"fv.x\"/><connect from=\"v.y\" to=\"fv.v\"/>\n"
      "<connect from=\"fx.y\" to=\"x.u\"/><connect from=\"fv.y\" to=\"v.u\"/>\n"
      "</connections>\n</diagram>\n");
  const Eigen::MatrixXd A = lin.Jacobian();
  EXPECT_NEAR(A(0, 0), -3 * 2.5 * 2.5, 1e-8);
  EXPECT_NEAR(A(0, 1), std::cos(0.7), 1e-8);
  EXPECT_NEAR(A(1, 0), -0.7, 1e-8);
  EXPECT_NEAR(A(1, 1), -2.5, 1e-8);
}

TEST(LinearizationTest, DampedOscillatorBlocksGivesFrequencyAndDampingRatio) {
  // x'' = -(c x + d v) / m with f = 1 Hz, zeta = 0.1: lambda = w (-zeta +- i
  // sqrt(1 - zeta^2)), damped frequency sqrt(0.99) = 0.994987 Hz.
  Linearised lin = FromFile("damped_oscillator_blocks.xml");
  const Eigen::MatrixXd A = lin.Jacobian();
  const StateRoles roles = FindStateRoles(A);
  const int x = lin.State("x.x"), v = lin.State("v.x");
  EXPECT_TRUE(roles.coordinate[x]);
  EXPECT_FALSE(roles.coordinate[v]);
  EXPECT_TRUE(roles.rate[v]);
  EXPECT_FALSE(roles.rate[x]);

  const auto modes = ModalAnalysis(A, roles.coordinate);
  ASSERT_EQ(modes.size(), 1u);
  const Mode& m = modes[0];
  EXPECT_EQ(m.kind, ModeKind::kOscillating);
  EXPECT_NEAR(m.frequency_hz, std::sqrt(0.99), 1e-6);
  EXPECT_NEAR(m.frequency_hz, 0.994987, 1e-6);
  EXPECT_NEAR(m.natural_frequency_hz, 1.0, 1e-6);
  EXPECT_NEAR(m.damping_ratio, 0.1, 1e-6);
  EXPECT_NEAR(m.eigenvalue.real(), -0.1 * 2 * kPi, 1e-6);
  EXPECT_NEAR(m.eigenvalue.imag(), std::sqrt(0.99) * 2 * kPi, 1e-6);
  EXPECT_NEAR(m.decay_rate, 0.2 * kPi, 1e-6);
  // shape: x is 1, v = lambda x, whose real part is Re lambda
  EXPECT_EQ(m.shape[x], 1.0);
  EXPECT_NEAR(m.shape[v], m.eigenvalue.real(), 1e-9);
}

// Mass and stiffness matrices of the three-mass chain (3, 2, 1 kg from the
// base up, springs of 1e5 N/m).
void ThreeMassMatrices(Eigen::MatrixXd* M, Eigen::MatrixXd* K) {
  const double c = 1e5;
  M->setZero(3, 3);
  M->diagonal() << 3, 2, 1;
  K->resize(3, 3);
  *K << 2 * c, -c, 0, -c, 2 * c, -c, 0, -c, c;
}

TEST(LinearizationTest, ThreeMassesBlocksGivesTheThreeNaturalFrequencies) {
  Linearised lin = FromFile("three_masses_blocks.xml");
  const Eigen::MatrixXd A = lin.Jacobian();
  const StateRoles roles = FindStateRoles(A);
  const auto modes = ModalAnalysis(A, roles.coordinate);
  ASSERT_EQ(modes.size(), 3u);
  const double seed[3] = {17.6613, 43.8189, 67.2512};  // ELEMENTS.md 9.8, to 4 decimals

  // independent: the generalized symmetric problem K phi = w^2 M phi
  Eigen::MatrixXd M, K;
  ThreeMassMatrices(&M, &K);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> reference(K, M);
  const int coordinate[3] = {lin.State("x1.x"), lin.State("x2.x"), lin.State("x3.x")};
  for (int k = 0; k < 3; ++k) {
    const Mode& m = modes[k];
    const double w = std::sqrt(reference.eigenvalues()(k));
    EXPECT_EQ(m.kind, ModeKind::kOscillating);
    EXPECT_NEAR(m.frequency_hz, seed[k], 1e-4);
    EXPECT_NEAR(m.natural_frequency_hz, seed[k], 1e-4);
    EXPECT_NEAR(m.frequency_hz, w / (2 * kPi), 1e-9 * w);
    EXPECT_EQ(m.damping_ratio, 0.0);
    // shape: the reference eigenvector scaled to its largest component
    Eigen::Vector3d phi = reference.eigenvectors().col(k);
    Eigen::Index largest;
    phi.cwiseAbs().maxCoeff(&largest);
    phi /= phi(largest);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(m.shape[coordinate[i]], phi(i), 1e-8) << "mode " << k + 1;
  }
  // the mechanism version of the same chain agrees
  Linearised mechanism = FromFile("frequencies.xml");
  const auto mechanism_modes = ModalAnalysis(mechanism.Jacobian());
  ASSERT_EQ(mechanism_modes.size(), 3u);
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(mechanism_modes[k].frequency_hz, modes[k].frequency_hz, 1e-8 * modes[k].frequency_hz);
}

// m x'' = -c x - d v - m g + k3-term, from an expression: started unloaded at
// x = 0, it hangs at -m g / c when k3 = 0.
std::string GravitySpring(double k3) {
  return "<diagram>\n<identifiers>\n"
         "<identifier name=\"m\" value=\"2\"/>\n"
         "<identifier name=\"c\" value=\"800\"/>\n"
         "<identifier name=\"d\" value=\"4\"/>\n"
         "<identifier name=\"k3\" value=\"" + std::to_string(k3) + "\"/>\n"
         "</identifiers>\n<blocks>\n"
         "<block type=\"integrator\" name=\"x\" initial=\"0\"/>\n"
         "<block type=\"integrator\" name=\"v\" initial=\"0.3\"/>\n"
         "<block type=\"expression\" name=\"a\" inputs=\"x v\" expr=\"(-c*x - k3*x^3 - d*v)/m - 9.81\"/>\n"
         "</blocks>\n<connections>\n"
         "<connect from=\"x.y\" to=\"a.x\"/><connect from=\"v.y\" to=\"a.v\"/>\n"
         "<connect from=\"a.y\" to=\"v.u\"/><connect from=\"v.y\" to=\"x.u\"/>\n"
         "</connections>\n</diagram>\n";
}

TEST(LinearizationTest, EquilibriumOfAMassOnASpringUnderGravity) {
  Linearised lin = FromXml(GravitySpring(0.0));
  const EquilibriumResult found = FindEquilibrium(lin.diagram(), &lin.ctx, &lin.x);
  const double m = 2, c = 800, d = 4, g = 9.81;
  // linear: one full Newton step lands on it (the FD Jacobian is exact)
  EXPECT_LE(found.iterations, 2);
  EXPECT_NEAR(lin.x[lin.State("x.x")], -m * g / c, 1e-12);
  EXPECT_NEAR(lin.x[lin.State("v.x")], 0.0, 1e-12);
  EXPECT_LE(found.residual, 1e-9);
  // the frequency there is that of the spring alone
  const auto modes = ModalAnalysis(lin.Jacobian());
  ASSERT_EQ(modes.size(), 1u);
  const double w = std::sqrt(c / m), zeta = d / (2 * std::sqrt(m * c));
  EXPECT_NEAR(modes[0].natural_frequency_hz, w / (2 * kPi), 1e-9);
  EXPECT_NEAR(modes[0].damping_ratio, zeta, 1e-9);
}

TEST(LinearizationTest, EquilibriumOfAHardeningSpringTakesSeveralNewtonSteps) {
  // c x + k3 x^3 = -m g with k3 large: Newton from x = 0 overshoots unless
  // damped; the root is checked by the residual of the cubic.
  Linearised lin = FromXml(GravitySpring(1e7));
  const EquilibriumResult found = FindEquilibrium(lin.diagram(), &lin.ctx, &lin.x);
  const double xe = lin.x[lin.State("x.x")];
  EXPECT_GT(found.iterations, 2);
  EXPECT_LT(xe, 0.0);
  EXPECT_NEAR(800 * xe + 1e7 * xe * xe * xe, -2 * 9.81, 1e-8);
  EXPECT_NEAR(lin.x[lin.State("v.x")], 0.0, 1e-12);
  // the rate at the equilibrium is stiffer than c alone: c + 3 k3 x^2
  const auto modes = ModalAnalysis(lin.Jacobian());
  ASSERT_EQ(modes.size(), 1u);
  // the step h = eps^(1/3) (|x| < 1) errs by h^2 k3 = 4e-4 in A(v, x) ~ 4e3:
  // 1e-7 relative, half that in the frequency
  const double f = std::sqrt((800 + 3e7 * xe * xe) / 2) / (2 * kPi);
  EXPECT_NEAR(modes[0].natural_frequency_hz, f, 1e-7 * f);
}

TEST(LinearizationTest, EquilibriumOfACubicDecayConvergesLinearlyWithinTheCap) {
  // x' = -x^3: A = -3 x^2 is singular at the root, Newton shrinks x by 2/3
  // per step; converged when |x^3| <= 1e-10 (1 + 3 |x|^3), about 19 steps.
  const std::string xml =
      "<diagram>\n<blocks>\n"
      "<block type=\"integrator\" name=\"x\" initial=\"1\"/>\n"
      "<block type=\"expression\" name=\"f\" inputs=\"x\" expr=\"-x^3\"/>\n"
      "</blocks>\n<connections>\n"
      "<connect from=\"x.y\" to=\"f.x\"/><connect from=\"f.y\" to=\"x.u\"/>\n"
      "</connections>\n</diagram>\n";
  Linearised lin = FromXml(xml);
  const EquilibriumResult found = FindEquilibrium(lin.diagram(), &lin.ctx, &lin.x);
  EXPECT_GE(found.iterations, 15);
  EXPECT_LE(found.iterations, 25);
  EXPECT_LE(std::abs(lin.x[0]), 1e-3);

  Linearised capped = FromXml(xml);
  try {
    FindEquilibrium(capped.diagram(), &capped.ctx, &capped.x, 1e-10, 5);
    FAIL() << "expected a SimulationError";
  } catch (const SimulationError& e) {
    // x after five steps: (2/3)^5 = 0.1317, rate -x^3
    const double x5 = std::pow(2.0 / 3.0, 5);
    EXPECT_NEAR(capped.x[0], x5, 1e-6);
    std::ostringstream rate;
    rate << -capped.x[0] * capped.x[0] * capped.x[0];
    EXPECT_EQ(std::string(e.what()),
              "no static equilibrium found: not converged after 5 Newton steps; the largest rate is " + rate.str() +
                  " (state 'x.x'). Is the diagram driven, or free to drift at a constant rate?");
  }
}

TEST(LinearizationTest, NoEquilibriumForAConstantDrift) {
  Linearised lin = FromXml(
      "<diagram>\n<blocks>\n"
      "<block type=\"integrator\" name=\"x\" initial=\"0\"/>\n"
      "<block type=\"constant\" name=\"one\" value=\"1\"/>\n"
      "</blocks>\n<connections>\n<connect from=\"one.y\" to=\"x.u\"/>\n</connections>\n</diagram>\n");
  try {
    FindEquilibrium(lin.diagram(), &lin.ctx, &lin.x);
    FAIL() << "expected a SimulationError";
  } catch (const SimulationError& e) {
    EXPECT_EQ(std::string(e.what()),
              "no static equilibrium found: Newton stalled (no step along the Newton direction reduces the rates) "
              "after 0 Newton steps; the largest rate is 1 (state 'x.x'). Is the diagram driven, or free to drift "
              "at a constant rate?");
  }
  EXPECT_EQ(lin.x[0], 0.0);
}

TEST(LinearizationTest, EquilibriumLeavesAFreeCoordinateWhereItIs) {
  // x1' = v1, v1' = 0 (free), x2' = v2, v2' = -x2 - 9.81: the least-norm step
  // moves only the spring's coordinate.
  Linearised lin = FromXml(
      "<diagram>\n<blocks>\n"
      "<block type=\"integrator\" name=\"x1\" initial=\"0.4\"/>\n"
      "<block type=\"integrator\" name=\"v1\" initial=\"0\"/>\n"
      "<block type=\"integrator\" name=\"x2\" initial=\"0\"/>\n"
      "<block type=\"integrator\" name=\"v2\" initial=\"0\"/>\n"
      "<block type=\"constant\" name=\"none\" value=\"0\"/>\n"
      "<block type=\"expression\" name=\"a2\" inputs=\"x\" expr=\"-x - 9.81\"/>\n"
      "</blocks>\n<connections>\n"
      "<connect from=\"v1.y\" to=\"x1.u\"/><connect from=\"none.y\" to=\"v1.u\"/>\n"
      "<connect from=\"v2.y\" to=\"x2.u\"/><connect from=\"x2.y\" to=\"a2.x\"/>\n"
      "<connect from=\"a2.y\" to=\"v2.u\"/>\n"
      "</connections>\n</diagram>\n");
  FindEquilibrium(lin.diagram(), &lin.ctx, &lin.x);
  EXPECT_EQ(lin.x[lin.State("x1.x")], 0.4);
  // converged to 1e-10 of the balancing terms (|x2| + 9.81 ~ 20); the FD
  // column of -x2 is exact only to rounding of 9.81 / h, so the last step
  // lands within about 1e-9 of the root
  EXPECT_NEAR(lin.x[lin.State("x2.x")], -9.81, 2e-9);
  const auto modes = ModalAnalysis(lin.Jacobian());
  ASSERT_EQ(modes.size(), 3u);  // a double zero (rigid body, twice) and the spring
  EXPECT_EQ(modes[0].kind, ModeKind::kRigidBody);
  EXPECT_EQ(modes[1].kind, ModeKind::kRigidBody);
  EXPECT_EQ(modes[2].kind, ModeKind::kOscillating);
  EXPECT_NEAR(modes[2].frequency_hz, 1 / (2 * kPi), 1e-12);
}

TEST(ModalAnalysisTest, ComplexPairKeptOnceWithClosedFormValues) {
  // A = [[0, 1], [-4, -0.4]]: lambda = -0.2 +- i sqrt(3.96), |lambda| = 2.
  Eigen::MatrixXd A(2, 2);
  A << 0, 1, -4, -0.4;
  const auto modes = ModalAnalysis(A);
  ASSERT_EQ(modes.size(), 1u);
  EXPECT_GT(modes[0].eigenvalue.imag(), 0.0);
  EXPECT_NEAR(modes[0].eigenvalue.imag(), std::sqrt(3.96), 1e-12);
  EXPECT_NEAR(modes[0].frequency_hz, std::sqrt(3.96) / (2 * kPi), 1e-12);
  EXPECT_NEAR(modes[0].natural_frequency_hz, 2 / (2 * kPi), 1e-12);
  EXPECT_NEAR(modes[0].damping_ratio, 0.1, 1e-12);
  // normalised on all states: the rate (|lambda| = 2 times larger) is 1
  EXPECT_EQ(modes[0].shape[1], 1.0);
}

TEST(ModalAnalysisTest, RealModesCarryTheirDecayRate) {
  // overdamped: x'' + 3 x' + 2 x = 0, lambda = -1, -2; and one growing state
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(3, 3);
  A(0, 1) = 1;
  A(1, 0) = -2;
  A(1, 1) = -3;
  A(2, 2) = 0.5;
  const auto modes = ModalAnalysis(A, {true, false, true});
  ASSERT_EQ(modes.size(), 3u);
  EXPECT_EQ(modes[0].kind, ModeKind::kGrowing);
  EXPECT_NEAR(modes[0].decay_rate, -0.5, 1e-12);
  EXPECT_NEAR(modes[0].damping_ratio, -1.0, 1e-12);
  for (int k = 1; k < 3; ++k) {
    EXPECT_EQ(modes[k].kind, ModeKind::kDecaying);
    EXPECT_EQ(modes[k].frequency_hz, 0.0);
    EXPECT_NEAR(modes[k].decay_rate, k, 1e-12);
    EXPECT_NEAR(modes[k].natural_frequency_hz, k / (2 * kPi), 1e-12);
    EXPECT_NEAR(modes[k].damping_ratio, 1.0, 1e-12);
    // shape: x = 1, v = lambda x = -k
    EXPECT_EQ(modes[k].shape[0], 1.0);
    EXPECT_NEAR(modes[k].shape[1], -k, 1e-12);
    EXPECT_NEAR(modes[k].shape[2], 0.0, 1e-12);
  }
}

TEST(ModalAnalysisTest, ShapePhaseMakesTheLargestCoordinateRealPositive) {
  // two undamped oscillators coupled, states (x1, x2, v1, v2); v-parts larger
  // than x-parts (w > 1), but the shapes are normalised on x
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(4, 4);
  A(0, 2) = A(1, 3) = 1;
  A(2, 0) = -200;
  A(2, 1) = 100;
  A(3, 0) = 100;
  A(3, 1) = -200;
  const StateRoles roles = FindStateRoles(A);
  EXPECT_EQ(roles.coordinate, (std::vector<bool>{true, true, false, false}));
  EXPECT_EQ(roles.rate, (std::vector<bool>{false, false, true, true}));
  const auto modes = ModalAnalysis(A, roles.coordinate);
  ASSERT_EQ(modes.size(), 2u);
  EXPECT_NEAR(modes[0].frequency_hz, 10 / (2 * kPi), 1e-10);
  EXPECT_NEAR(modes[1].frequency_hz, std::sqrt(300.0) / (2 * kPi), 1e-10);
  // in phase, then in opposition; rates imaginary, so real part 0
  EXPECT_NEAR(std::abs(modes[0].shape[0]), 1.0, 1e-12);
  EXPECT_NEAR(modes[0].shape[1], modes[0].shape[0], 1e-12);
  EXPECT_NEAR(modes[1].shape[1], -modes[1].shape[0], 1e-12);
  for (const Mode& m : modes) {
    EXPECT_EQ(std::max(m.shape[0], m.shape[1]), 1.0);
    EXPECT_NEAR(m.shape[2], 0.0, 1e-12);
    EXPECT_NEAR(m.shape[3], 0.0, 1e-12);
  }
}

TEST(ModalAnalysisTest, EmptyMatrixHasNoModes) { EXPECT_TRUE(ModalAnalysis(Eigen::MatrixXd(0, 0)).empty()); }

}  // namespace
}  // namespace mechflow::analysis
