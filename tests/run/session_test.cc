// run::Session: a run taken in steps gives the rows of the run taken whole,
// bit for bit, when it pauses at the output times (in the middle of the
// integrator's steps), and the same to the tolerance's order when it pauses
// between them; an input set between steps holds from then on.

#include "run/session.h"

#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "diagrams/xml_reader.h"
#include "run/sinks.h"

namespace mechflow {
namespace {

std::string ExampleFile(const std::string& name) {
  return std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/" + name;
}

std::vector<std::vector<double>> WholeRun(run::Model& model) {
  run::MemorySink sink;
  const run::RunResult r = model.Run({}, &sink);
  EXPECT_EQ(r.status, run::Status::kOk) << r.reason;
  return sink.columns();
}

// Each example: stick-slip events, an algebraic loop, a sampled Lua control.
TEST(RunSession, PausingAtOutputTimesGivesTheWholeRunsRowsBitForBit) {
  for (const char* example : {"stick_slip_blocks.xml", "cart_pendulum_friction.xml", "pendulum_pd_control.xml"}) {
    run::Model model(ExampleFile(example));
    const std::vector<std::vector<double>> whole = WholeRun(model);
    run::Session session(model);
    session.Start();
    for (std::size_t row = 0; row < whole[0].size(); ++row) {
      if (row > 0) { ASSERT_TRUE(session.AdvanceTo(whole[0][row])) << example << ": " << session.failure(); }
      const std::vector<double>& now = session.Row();
      for (std::size_t c = 0; c < whole.size(); ++c)
        ASSERT_EQ(now[c], whole[c][row]) << example << ", column " << c << ", t = " << whole[0][row];
    }
    EXPECT_EQ(session.Finish().status, run::Status::kOk) << example;
  }
}

TEST(RunSession, PausingBetweenOutputTimesStaysWithinTheTolerance) {
  run::Model model(ExampleFile("stick_slip_blocks.xml"));  // rtol 1e-8, rows every 1 ms
  const std::vector<std::vector<double>> whole = WholeRun(model);
  run::Session session(model);
  session.Start();
  double worst = 0.0;
  for (std::size_t row = 10; row < whole[0].size(); row += 10) {
    ASSERT_TRUE(session.AdvanceTo(whole[0][row] - 3.7e-4));  // a pause between rows, then the row
    ASSERT_TRUE(session.AdvanceTo(whole[0][row]));
    worst = std::max(worst, std::abs(session.Row()[1] - whole[1][row]));
  }
  EXPECT_LT(worst, 1e-6);  // x is of order 0.04 m
}

TEST(RunSession, AnInputHoldsFromTheTimeItIsSet) {
  const std::string xml = R"(<diagram name="held">
  <input name="u" unit="mm" start="2" comment="a rate"/>
  <blocks><block type="integrator" name="x"/></blocks>
  <connections><connect from="u" to="x"/></connections>
  <solver t_end="2"/>
  <output interval="0.5"><log signal="x"/><log signal="u" label="rate"/></output>
</diagram>)";
  run::Model model(diagrams::ReadDiagramText(xml, "held.xml"));
  ASSERT_EQ(model.Loaded().inputs.size(), 1u);
  EXPECT_EQ(model.Loaded().inputs[0].start, 0.002);  // start in mm, SI inside
  run::Session session(model);
  session.Start();
  ASSERT_TRUE(session.AdvanceTo(1.0));
  EXPECT_NEAR(session.Row()[1], 0.002, 1e-15);
  session.SetInput(0, -3.0);  // mm
  EXPECT_EQ(session.Input(0), -3.0);
  EXPECT_EQ(session.Row()[0], 1.0);
  EXPECT_NEAR(session.Row()[2], -0.003, 1e-18);  // fed through at once
  EXPECT_NEAR(session.Row()[1], 0.002, 1e-15);   // the state is where it was
  ASSERT_TRUE(session.AdvanceTo(1.5));
  EXPECT_NEAR(session.Row()[1], 0.002 - 0.0015, 1e-15);
  EXPECT_NEAR(session.Row()[2], -0.003, 1e-18);
  // mechflow run holds the start value
  run::MemorySink sink;
  model.Run({}, &sink);
  EXPECT_NEAR(sink.columns()[1].back(), 0.004, 1e-15);
}

}  // namespace
}  // namespace mechflow
