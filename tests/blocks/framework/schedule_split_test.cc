// The schedule split (Diagram::dynamics_schedule / rest_schedule): a
// right-hand side or a root check computes only the outputs that derivatives
// and zero crossings read; an output that is only logged is computed for the
// rows, where it has the value the whole schedule would give it.

#include <cmath>

#include <gtest/gtest.h>

#include "blocks/framework/diagram.h"
#include "tests/blocks/block_test_util.h"

namespace mechflow::blocks::testing {
namespace {

// y = k u, counting its evaluations.
class CountingGain : public Block {
 public:
  CountingGain(std::string name, double k, int* calls) : Block("counting_gain", name), k_(k), calls_(calls) {
    DeclareInputPort("u");
    DeclareOutputPort("y");
  }

 protected:
  void DoCalcOutput(int, const BlockContext& ctx) const override {
    ++*calls_;
    ctx.output(0)[0] = k_ * ctx.input_scalar(0);
  }

 private:
  double k_;
  int* calls_;
};

bool Contains(const std::vector<OutputNode>& entries, const Diagram& d, const std::string& block) {
  for (const OutputNode& node : entries)
    if (node.block == d.FindBlock(block)) return true;
  return false;
}

// x' = -2 x (x = exp(-2 t)) through the counted gain `fed`; `seen` = 3 x is
// logged only; a step at t = 5 adds a root function checked at every step
// and output time (its evaluation is the one a row then completes).
TEST(ScheduleSplitTest, OutputsOnlyLoggedAreComputedForRowsAlone) {
  int fed_calls = 0, seen_calls = 0;
  const testing::Run run = Simulate(Blocks(MakeBlock("integrator", "x", {{"initial", "1"}}),
                                  std::make_unique<CountingGain>("fed", -2.0, &fed_calls),
                                  std::make_unique<CountingGain>("seen", 3.0, &seen_calls),
                                  MakeBlock("step", "later", {{"time", "5"}}), MakeBlock("gain", "unread", {{"k", "2"}})),
                           {{"x.y", "fed.u"}, {"fed.y", "x.u"}, {"x.y", "seen.u"}, {"later.y", "unread.u"}},
                           {"x.y", "seen.y"}, Options(1.0, 0.1));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const Diagram& d = *run.diagram;
  EXPECT_TRUE(Contains(d.dynamics_schedule(), d, "fed"));
  EXPECT_TRUE(Contains(d.dynamics_schedule(), d, "x"));
  for (const char* rest : {"seen", "later", "unread"}) {
    EXPECT_FALSE(Contains(d.dynamics_schedule(), d, rest)) << rest;
    EXPECT_TRUE(Contains(d.rest_schedule(), d, rest)) << rest;
  }
  EXPECT_EQ(d.dynamics_schedule().size() + d.rest_schedule().size(), d.schedule().size());

  const auto t = run.Time(), x = run.Column("x.y"), seen = run.Column("seen.y");
  ASSERT_EQ(t.size(), 11u);
  for (std::size_t i = 0; i < t.size(); ++i) {
    EXPECT_NEAR(x[i], std::exp(-2.0 * t[i]), 1e-8) << t[i];
    EXPECT_EQ(seen[i], 3.0 * x[i]) << t[i];
  }
  const long rhs = run.sim->stats().rhs_evals;
  EXPECT_GE(fed_calls, rhs);
  // one per row, and the few evaluations of the start (initial modes)
  EXPECT_GE(seen_calls, 11);
  EXPECT_LE(seen_calls, 11 + 5) << "right-hand sides: " << rhs;
  EXPECT_GT(rhs, 5 * 11);  // so that counting tells the two apart
}

// An algebraic loop is solved as a whole: when one of its outputs feeds a
// derivative, the loop is in the dynamics schedule; a loop that is only
// logged is not.
TEST(ScheduleSplitTest, LoopsGoWholeIntoOneSchedule) {
  // fed loop: s = x + 0.5 s feeds x' = -s; logged loop: r = 1 + 0.5 r
  const testing::Run run = Simulate(
      Blocks(MakeBlock("integrator", "x", {{"initial", "1"}}), MakeBlock("gain", "neg", {{"k", "-1"}}),
             MakeBlock("gain", "h", {{"k", "0.5"}}), MakeBlock("sum", "s"), MakeBlock("constant", "c", {{"value", "1"}}),
             MakeBlock("gain", "k", {{"k", "0.5"}}), MakeBlock("sum", "r")),
      {{"x.y", "s.u1"}, {"h.y", "s.u2"}, {"s.y", "h.u"}, {"s.y", "neg.u"}, {"neg.y", "x.u"}, {"c.y", "r.u1"},
       {"k.y", "r.u2"}, {"r.y", "k.u"}},
      {"x.y", "s.y", "r.y"}, Options(1.0, 0.1));
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  const Diagram& d = *run.diagram;
  ASSERT_EQ(d.loops().size(), 2u);
  int dynamics_loops = 0, rest_loops = 0;
  for (const OutputNode& node : d.dynamics_schedule()) dynamics_loops += node.loop >= 0;
  for (const OutputNode& node : d.rest_schedule()) rest_loops += node.loop >= 0;
  EXPECT_EQ(dynamics_loops, 1);
  EXPECT_EQ(rest_loops, 1);
  EXPECT_FALSE(Contains(d.dynamics_schedule(), d, "c"));
  const auto t = run.Time(), x = run.Column("x.y"), s = run.Column("s.y"), r = run.Column("r.y");
  for (std::size_t i = 0; i < t.size(); ++i) {
    EXPECT_NEAR(x[i], std::exp(-2.0 * t[i]), 1e-8);
    EXPECT_NEAR(s[i], 2.0 * x[i], 1e-11);
    EXPECT_NEAR(r[i], 2.0, 1e-12);
  }
}

}  // namespace
}  // namespace mechflow::blocks::testing
