// The animation's recorder (graphics/recorder.h): frames at the display
// rate with the run's last row last, poses equal to the kinematics, shapes
// read again when a script changes their identifiers, and memory bounded on
// long runs (every other frame or version dropped, the spacing doubled).

#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "blocks/simulator.h"
#include "graphics/recorder.h"
#include "tests/test_util.h"

namespace mechflow::graphics {
namespace {

// A body driven along z as z = t, logged.
const char* kDriven =
    "<diagram name='d'><mechanism name='m'><body name='B' mass='1' inertia='1 1 1'/>"
    "<joint name='j' type='generalized' body1='Base0' body2='B'><et type='tt' axis='0 0 1' value='t'/></joint>"
    "<shape type='box' body='B'/><sensor name='z' kind='position' body='B' component='z'/></mechanism>"
    "<solver t_end='2'/><output interval='0.001'><log signal='m.z'/></output></diagram>";

struct Recorded {
  diagrams::LoadedDiagram loaded;
  Scene scene;
  std::unique_ptr<AnimationRecorder> recorder;
};

std::unique_ptr<Recorded> Record(diagrams::LoadedDiagram loaded, RecorderOptions options) {
  auto r = std::make_unique<Recorded>(Recorded{std::move(loaded), {}, nullptr});
  r->scene = BuildScene(r->loaded);
  blocks::Simulator sim(*r->loaded.diagram, r->loaded.solver, r->loaded.logged);
  sim.SetControl(r->loaded.control.get());
  r->recorder = std::make_unique<AnimationRecorder>(r->loaded, r->scene, std::vector<std::string>{"z"}, options);
  sim.SetRowObserver(r->recorder.get());
  EXPECT_TRUE(sim.Run().ok);
  return r;
}

TEST(RecorderTest, FramesAreAtTheDisplayRateWithTheLastRowLast) {
  const auto r = Record(mechflow::testing::LoadXml(kDriven), {});
  const AnimationRecorder& rec = *r->recorder;
  ASSERT_EQ(rec.times().size(), 224u);  // rows 9 ms apart (the first at least 1/120 s) to 1.998 s, and t = 2
  EXPECT_DOUBLE_EQ(rec.times().front(), 0.0);
  EXPECT_NEAR(rec.times().back(), 2.0, 1e-12);
  for (std::size_t f = 0; f < rec.times().size(); ++f) {
    EXPECT_NEAR(rec.Pose(static_cast<int>(f), 0).p.z(), rec.times()[f], 1e-6);
    EXPECT_NEAR(rec.signals()[f], rec.times()[f], 1e-6);  // the logged z
  }
}

TEST(RecorderTest, LongRunsKeepABoundedNumberOfFrames) {
  RecorderOptions options;
  options.max_frames = 100;
  const auto r = Record(mechflow::testing::LoadXml(kDriven), options);
  const AnimationRecorder& rec = *r->recorder;
  EXPECT_LE(rec.times().size(), 101u);
  EXPECT_GE(rec.times().size(), 50u);
  EXPECT_DOUBLE_EQ(rec.times().front(), 0.0);
  EXPECT_NEAR(rec.times().back(), 2.0, 1e-12);
  for (std::size_t f = 0; f < rec.times().size(); ++f) {
    EXPECT_NEAR(rec.Pose(static_cast<int>(f), 0).p.z(), rec.times()[f], 1e-6);
    if (f > 0 && f + 1 < rec.times().size()) {
      EXPECT_GE(rec.times()[f] - rec.times()[f - 1], 4 / 120.0 - 1e-9);
    }
  }
}

TEST(RecorderTest, ShapesFollowTheScriptsIdentifiersWithinABoundedMemory) {
  const std::string molecule = std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/molecule.xml";
  const auto r = Record(diagrams::LoadDiagram(molecule), {});
  const std::size_t versions = r->recorder->versions().size();
  EXPECT_EQ(versions, 29u);  // from 0.01 s every 0.07 s (at least 1/15 s on the 0.01 s grid): to 1.97 s
  EXPECT_NEAR(r->recorder->versions()[1].t - r->recorder->versions()[0].t, 0.07, 1e-9);

  RecorderOptions options;
  options.max_version_bytes = 8 * 33 * 17 * 3 * sizeof(float);  // eight versions of the 32 x 16 surface
  const auto bounded = Record(diagrams::LoadDiagram(molecule), options);
  EXPECT_LE(bounded->recorder->versions().size(), 8u);
  EXPECT_GE(bounded->recorder->versions().size(), 4u);
  EXPECT_TRUE(bounded->recorder->warnings().empty());
}

}  // namespace
}  // namespace mechflow::graphics
