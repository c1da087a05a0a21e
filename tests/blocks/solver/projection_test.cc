// Projection onto a manifold after each solver step (CVODE's projection hook),
// on a point that circles the unit circle with a deliberate radial drift.

#include <cmath>
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "blocks/framework/diagram_builder.h"
#include "blocks/solver/simulator.h"
#include "mech/errors.h"

namespace mechflow::blocks::projection_test {  // names of its own: the files of its folder are compiled together
namespace {

// A point circling the unit circle at w [rad/s] with a radial term that
// pushes it off the circle: x' = -w y + k (r^2 - 1) x, y' = w x + k (r^2 - 1) y,
// so r' = k (r^2 - 1) r. The circle is invariant but unstable: the solver's
// own errors grow as exp(2 k t) and the point spirals away (to the origin or
// to infinity). With projection, each step is pulled back radially.
// (A drift that the exact flow has, such as + eps x, is no case for
// projection: it fights the equations, and CVODE crawls at tiny steps.)
// Outputs: "x", "y" and "r" (the radius). After `fail_after` [s] projection
// throws, to test how a failed projection ends the run.
class UnstableCircle : public Block {
 public:
  UnstableCircle(std::string name, double w, double k, bool project, double fail_after = INFINITY)
      : Block("unstable_circle", std::move(name)), w_(w), k_(k), fail_after_(fail_after) {
    DeclareOutputPort("x");
    DeclareOutputPort("y");
    DeclareOutputPort("r");
    DeclareNoFeedthrough();
    DeclareContinuousStates(2);
    if (project) DeclareProjection();
  }

  // The width of the error slice the solver passed last (-1: never called).
  int error_width_seen() const { return error_width_seen_; }

 protected:
  void DoInitialize(const BlockContext& ctx) const override {
    ctx.state()[0] = 1.0;  // on the manifold: the solver projects only after steps
    ctx.state()[1] = 0.0;
  }
  void DoCalcOutput(int port, const BlockContext& ctx) const override {
    const auto s = ctx.state();
    ctx.output(port)[0] = port == 0 ? s[0] : port == 1 ? s[1] : std::hypot(s[0], s[1]);
  }
  void DoCalcDerivatives(const BlockContext& ctx) const override {
    const auto s = ctx.state();
    const double radial = k_ * (s[0] * s[0] + s[1] * s[1] - 1.0);
    ctx.derivative()[0] = -w_ * s[1] + radial * s[0];
    ctx.derivative()[1] = w_ * s[0] + radial * s[1];
  }
  void DoProject(const BlockContext& ctx, std::span<double> correction, std::span<double> error,
                 std::span<const double>) const override {
    error_width_seen_ = static_cast<int>(error.size());
    if (ctx.time() > fail_after_) throw SimulationError("unstable_circle: cannot project at this time");
    const auto s = ctx.state();
    const double r = std::hypot(s[0], s[1]);
    if (!(r > 0.0) || !std::isfinite(r)) throw SimulationError("unstable_circle: no direction to project along");
    correction[0] = s[0] / r - s[0];
    correction[1] = s[1] / r - s[1];
    // the error estimate is left alone (see Block::Project)
  }

 private:
  double w_, k_, fail_after_;
  mutable int error_width_seen_ = -1;  // test instrumentation only
};

// x' = a x, y = x: a block that knows nothing of projection.
class Exponential : public Block {
 public:
  Exponential(std::string name, double a) : Block("exponential", std::move(name)), a_(a) {
    DeclareOutputPort("y");
    DeclareNoFeedthrough();
    DeclareContinuousStates(1);
  }

 protected:
  void DoInitialize(const BlockContext& ctx) const override { ctx.state()[0] = 1.0; }
  void DoCalcOutput(int, const BlockContext& ctx) const override { ctx.output(0)[0] = ctx.state()[0]; }
  void DoCalcDerivatives(const BlockContext& ctx) const override { ctx.derivative()[0] = a_ * ctx.state()[0]; }

 private:
  double a_;
};

// A periodic block with nothing to compute: each hit re-initialises CVODE.
class Ticker : public Block {
 public:
  explicit Ticker(double period) : Block("ticker", "tick") {
    DeclareOutputPort("y");
    DeclareNoFeedthrough();
    DeclarePeriodicSampleTime(period, 0.0);
  }

 protected:
  void DoCalcOutput(int, const BlockContext& ctx) const override { ctx.output(0)[0] = 0.0; }
};

constexpr double kOmega = 1.0;    // [rad/s]
constexpr double kUnstable = 0.2;  // [1/s]: errors grow as exp(0.4 t), 2e17 over 100 s

SolverOptions Options(double t_end) {
  SolverOptions options;
  options.t_end = t_end;
  options.rtol = 1e-9;
  options.atol = 1e-11;
  options.output_interval = 0.1;
  return options;
}

double LargestRadiusError(const Results& r, int column) {
  double worst = 0.0;
  for (int i = 0; i < r.num_rows(); ++i) worst = std::max(worst, std::abs(r.at(i, column) - 1.0));
  return worst;
}

TEST(ProjectionTest, KeepsTheCircleOnTheUnitCircle) {
  DiagramBuilder builder;
  auto& circle = static_cast<UnstableCircle&>(
      builder.AddBlock(std::make_unique<UnstableCircle>("c", kOmega, kUnstable, true)));
  auto diagram = builder.Build();
  Simulator sim(*diagram, Options(100.0),
                {diagram->ResolveSignal("c.x"), diagram->ResolveSignal("c.y"), diagram->ResolveSignal("c.r")});
  const RunOutcome outcome = sim.Run();
  ASSERT_TRUE(outcome.ok) << outcome.failure;
  const Results& r = sim.results();
  ASSERT_EQ(r.num_rows(), 1001);
  // rows come from CVODE's interpolant between projected steps (1.4e-11 measured)
  EXPECT_LT(LargestRadiusError(r, 3), 1e-10);
  // on the circle the radial term vanishes: the point turns at w
  for (int i = 0; i < r.num_rows(); ++i) {
    const double t = r.at(i, 0);
    ASSERT_NEAR(r.at(i, 1), std::cos(kOmega * t), 1e-6) << "t = " << t;
    ASSERT_NEAR(r.at(i, 2), std::sin(kOmega * t), 1e-6) << "t = " << t;
  }
  const SolverStats& stats = sim.stats();
  EXPECT_GT(stats.projections, 0);
  EXPECT_LE(stats.projections, stats.steps + stats.error_test_failures + stats.newton_failures);
  EXPECT_EQ(stats.projection_failures, 0);
  // CVODE projects its error estimate by default: the block gets its slice
  EXPECT_EQ(circle.error_width_seen(), 2);
}

TEST(ProjectionTest, WithoutProjectionTheRadiusDrifts) {
  DiagramBuilder builder;
  auto& circle = static_cast<UnstableCircle&>(
      builder.AddBlock(std::make_unique<UnstableCircle>("c", kOmega, kUnstable, false)));
  auto diagram = builder.Build();
  Simulator sim(*diagram, Options(100.0), {diagram->ResolveSignal("c.r")});
  const RunOutcome outcome = sim.Run();
  // the point leaves the circle: it spirals in (or away to infinity, which fails the run)
  const Results& r = sim.results();
  ASSERT_GT(r.num_rows(), 10) << outcome.failure;
  EXPECT_GT(LargestRadiusError(r, 1), 0.1);
  EXPECT_EQ(sim.stats().projections, 0);
  EXPECT_EQ(sim.stats().projection_failures, 0);
  EXPECT_EQ(circle.error_width_seen(), -1) << "a block without projection was asked to project";
}

TEST(ProjectionTest, BlocksWithoutProjectionAreLeftAlone) {
  // alone: the solver never projects
  {
    DiagramBuilder builder;
    builder.AddBlock(std::make_unique<Exponential>("e", -0.5));
    auto diagram = builder.Build();
    Simulator sim(*diagram, Options(10.0), {diagram->ResolveSignal("e.y")});
    const RunOutcome outcome = sim.Run();
    ASSERT_TRUE(outcome.ok) << outcome.failure;
    EXPECT_EQ(sim.stats().projections, 0);
  }
  // beside a projecting block: its states are not corrected
  DiagramBuilder builder;
  builder.AddBlock(std::make_unique<Exponential>("e", -0.5));
  builder.AddBlock(std::make_unique<UnstableCircle>("c", kOmega, kUnstable, true));
  auto diagram = builder.Build();
  Simulator sim(*diagram, Options(10.0), {diagram->ResolveSignal("e.y"), diagram->ResolveSignal("c.r")});
  const RunOutcome outcome = sim.Run();
  ASSERT_TRUE(outcome.ok) << outcome.failure;
  EXPECT_GT(sim.stats().projections, 0);
  const Results& r = sim.results();
  for (int i = 0; i < r.num_rows(); ++i) {
    ASSERT_NEAR(r.at(i, 1), std::exp(-0.5 * r.at(i, 0)), 1e-7) << "t = " << r.at(i, 0);
    ASSERT_NEAR(r.at(i, 2), 1.0, 1e-10) << "t = " << r.at(i, 0);
  }
}

TEST(ProjectionTest, CountersAddUpOverReinitialisations) {
  // CVODE restarts its counters at every re-initialisation; the run's totals
  // still count each projection once
  DiagramBuilder builder;
  builder.AddBlock(std::make_unique<UnstableCircle>("c", kOmega, kUnstable, true));
  builder.AddBlock(std::make_unique<Ticker>(0.5));
  auto diagram = builder.Build();
  Simulator sim(*diagram, Options(20.0), {diagram->ResolveSignal("c.r")});
  const RunOutcome outcome = sim.Run();
  ASSERT_TRUE(outcome.ok) << outcome.failure;
  const SolverStats& stats = sim.stats();
  EXPECT_EQ(stats.reinits, 39);
  EXPECT_GE(stats.projections, stats.steps);
  EXPECT_LE(stats.projections, stats.steps + stats.error_test_failures + stats.newton_failures);
  // restarts at order 1 interpolate a little worse (1.2e-10 measured)
  EXPECT_LT(LargestRadiusError(sim.results(), 1), 1e-9);
}

TEST(ProjectionTest, AFailedProjectionEndsTheRunWithTheBlocksReason) {
  DiagramBuilder builder;
  builder.AddBlock(std::make_unique<UnstableCircle>("c", kOmega, kUnstable, true, 2.0));
  auto diagram = builder.Build();
  Simulator sim(*diagram, Options(10.0), {diagram->ResolveSignal("c.r")});
  const RunOutcome outcome = sim.Run();
  ASSERT_FALSE(outcome.ok);
  EXPECT_NE(outcome.failure.find("cannot project at this time"), std::string::npos) << outcome.failure;
  EXPECT_NEAR(outcome.t_reached, 2.0, 0.1);
  EXPECT_GT(sim.stats().projection_failures, 0);
  // the rows up to the failure are kept
  const Results& r = sim.results();
  ASSERT_GE(r.num_rows(), 20);
  EXPECT_LE(r.at(r.num_rows() - 1, 0), 2.0 + 1e-12);
}

}  // namespace
}  // namespace mechflow::blocks::projection_test
