// Sticking without chatter or creep at the solver's default accuracy
// (the seed promises that the frictional type shows no high-frequency chatter
// at stick at rtol 1e-6): the ElastFriction Free variant (box 10 kg at 1.5 m/s,
// sliding force 10 N) run at rtol 1e-6, atol 1e-8 instead of the diagram's
// 1e-8 / 1e-10.

#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "blocks/solver/simulator.h"
#include "diagrams/loader.h"
#include "tests/test_util.h"

namespace mechflow {
namespace {

TEST(FrictionStickTest, FrictionalStopsOnceAndHoldsAtRtol1e6) {
  diagrams::LoadOptions options;
  auto loaded =
      diagrams::LoadDiagram(std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/elast_friction.xml", options);
  loaded.solver.rtol = 1e-6;
  loaded.solver.atol = 1e-8;
  blocks::Simulator sim(*loaded.diagram, loaded.solver, loaded.logged);
  const blocks::RunOutcome outcome = sim.Run();
  ASSERT_TRUE(outcome.ok) << outcome.failure;
  // One event only: the stop. Chatter would show as stick/slip switches.
  ASSERT_EQ(sim.events().size(), 1u);
  EXPECT_NEAR(sim.events()[0].time, 1.5, 1.5e-3);
  const blocks::Results& r = sim.results();
  const auto t = r.Column(0), x = r.Column(r.FindColumn("m.x")), v = r.Column(r.FindColumn("m.v")),
             mode = r.Column(r.FindColumn("m.mode"));
  double x_stop = 0.0, creep = 0.0, speed = 0.0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (t[i] < 1.51) {
      x_stop = x[i];
      continue;
    }
    ASSERT_EQ(mode[i], 0.0) << "not stuck at t = " << t[i];
    creep = std::max(creep, std::abs(x[i] - x_stop));
    speed = std::max(speed, std::abs(v[i]));
  }
  EXPECT_NEAR(x_stop, 1.125, 1.125e-3);
  // The stick spring takes no load here (nothing pushes the box), so any
  // motion after the stop would be numerical: bounds far below the tolerances.
  EXPECT_LT(creep, 1e-9);
  EXPECT_LT(speed, 1e-9);
}

// A push below the break-away force is held by the stick spring: its
// deflection sensor reads push / c, and the box rests there.
TEST(FrictionStickTest, DeflectionSensorHoldsThePush) {
  const auto run = testing::RunXml(R"xml(<diagram>
  <mechanism name="m" gravity="0 0 0">
    <body name="Box" mass="10" inertia="1 1 1"/>
    <joint name="jBox" type="translational" body1="Base0" body2="Box" axis="1 0 0"/>
    <joint_force name="push" dof="jBox" type="expression" expression="5"/>
    <force name="friction" type="frictional" body1="Base0" point1="-1 0 0" body2="Box"
           friction="10" ratio="1.2" c="1e4" d="2*sqrt(10*1e4)"/>
    <sensor name="x" kind="coordinate" dof="jBox"/>
    <sensor name="deflection" kind="element" element="friction" quantity="deflection"/>
    <sensor name="force" kind="element" element="friction"/>
  </mechanism>
  <solver t_end="2" rtol="1e-8" atol="1e-12"/>
  <output interval="0.01">
    <log signal="m.x"/><log signal="m.deflection"/><log signal="m.force"/>
  </output>
</diagram>)xml");
  ASSERT_TRUE(run.outcome.ok) << run.outcome.failure;
  EXPECT_TRUE(run.sim->events().empty());  // never breaks away
  EXPECT_NEAR(run.Column("m.deflection").back(), 5e-4, 1e-9);
  EXPECT_NEAR(run.Column("m.x").back(), 5e-4, 1e-9);  // the box starts at the anchor
  EXPECT_NEAR(run.Column("m.force").back(), -5.0, 1e-5);
}

TEST(FrictionStickTest, AHeldBlockCostsNoMoreStepsAtATightAtol) {
  // Round-off must not cost steps: a block held on a 30 degree slope by a
  // frictional element with a stiff stick spring (1e7 N/m). Its deflection
  // was formed from absolute lengths, whose round-off times the spring made
  // noise that a tight atol chased: 135956 steps at atol 1e-14 against 647 at
  // 1e-10. Integrated from the rate, it takes 1859 against 897.
  auto run = [](const std::string& atol) {
    return testing::RunXml(
        "<diagram name='held'><mechanism name='m'><body name='B' mass='1' inertia='1 1 1'/>"
        "<joint name='j' type='translational' body1='Base0' body2='B' axis='0.8660254037844386 0 0.5' q0='1'/>"
        "<force name='hold' type='frictional' body1='Base0' point1='0 0 0' body2='B' point2='0 0 0' "
        "friction='10' ratio='1.2' c='1e7' d='1e3'/>"
        "<sensor name='s' kind='coordinate' dof='j'/><sensor name='mode' kind='element' element='hold' "
        "quantity='mode'/></mechanism><solver t_end='10' rtol='1e-8' atol='" +
        atol + "'/><output interval='0.1'><log signal='m.s'/><log signal='m.mode'/></output></diagram>");
  };
  const auto loose = run("1e-10"), tight = run("1e-14");
  ASSERT_TRUE(loose.outcome.ok) << loose.outcome.failure;
  ASSERT_TRUE(tight.outcome.ok) << tight.outcome.failure;
  EXPECT_LT(tight.sim->stats().steps, 4 * loose.sim->stats().steps);
  // held: the spring deflects by m g sin(30 deg) / c and stays there
  EXPECT_NEAR(tight.Column("m.s").back(), 1.0 - 9.81 * 0.5 / 1e7, 1e-12);
  EXPECT_EQ(tight.Column("m.mode").back(), 0.0);
}

}  // namespace
}  // namespace mechflow
