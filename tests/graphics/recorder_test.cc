// The animation's recorder (graphics/recorder.h): frames at the display
// rate with the run's last row last, poses equal to the kinematics, shapes
// read again when a script changes their identifiers, and memory bounded on
// long runs (every other frame or version dropped, the spacing doubled);
// the logged signals at every row, a long run's as the extremes of bins of
// time that keep every peak.

#include <algorithm>
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "blocks/solver/simulator.h"
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
  for (std::size_t f = 0; f < rec.times().size(); ++f)
    EXPECT_NEAR(rec.Pose(static_cast<int>(f), 0).p.z(), rec.times()[f], 1e-6);
}

TEST(RecorderTest, TheSignalsAreKeptAtEveryRow) {
  const auto r = Record(mechflow::testing::LoadXml(kDriven), {});
  const SignalTrack& track = r->recorder->signals();
  EXPECT_FALSE(track.binned());
  const std::vector<double> times = track.Times(), values = track.Values();
  ASSERT_EQ(times.size(), 2001u);  // rows 1 ms apart, not the frames' 9 ms
  ASSERT_EQ(values.size(), 2001u);
  for (std::size_t i = 0; i < times.size(); ++i) EXPECT_NEAR(values[i], times[i], 1e-12);  // the logged z, in double
}

// A spike of one row among many (an end stop's hit in a long run): binned,
// the track keeps it, and the sine's crests and troughs, in at most its
// bound of points.
TEST(SignalTrackTest, ALongRunsBinsKeepEveryExtreme) {
  constexpr int kRows = 100001;
  SignalTrack track(2, 0.0, 100.0, 64);
  for (int r = 0; r < kRows; ++r) {
    const double t = r * 0.001, row[2] = {r == 54321 ? 7.5 : std::sin(t), r == 777 ? -3.0 : 0.0};
    track.Add(t, row);
  }
  ASSERT_TRUE(track.binned());
  const std::vector<double> times = track.Times(), values = track.Values();
  ASSERT_LE(times.size(), 64u);
  ASSERT_GE(times.size(), 32u);
  ASSERT_EQ(values.size(), 2 * times.size());
  EXPECT_EQ(times.front(), 0.0);
  EXPECT_NEAR(times.back(), 100.0, 1e-9);
  double high = -1e9, low = 1e9, low_other = 1e9, high_sine_elsewhere = -1e9;
  for (std::size_t p = 0; p < times.size(); ++p) {
    if (p > 0) {
      EXPECT_GE(times[p], times[p - 1]);
    }
    high = std::max(high, values[2 * p]);
    low = std::min(low, values[2 * p]);
    low_other = std::min(low_other, values[2 * p + 1]);
    if (std::abs(times[p] - 54.321) > 5) high_sine_elsewhere = std::max(high_sine_elsewhere, values[2 * p]);
  }
  EXPECT_EQ(high, 7.5);
  EXPECT_EQ(low_other, -3.0);
  EXPECT_NEAR(low, -1.0, 1e-6);  // the sine's troughs and crests survive too
  EXPECT_NEAR(high_sine_elsewhere, 1.0, 1e-6);
}

TEST(SignalTrackTest, UpToItsBoundEveryRowIsKept) {
  SignalTrack track(1, 0.0, 1.0, 64);
  for (int r = 0; r < 64; ++r) {
    const double v = r % 2 ? 1.0 : -1.0;
    track.Add(r / 63.0, &v);
  }
  EXPECT_FALSE(track.binned());
  EXPECT_EQ(track.Times().size(), 64u);
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
