#pragma once
// AnimationRecorder: what the animation shows, recorded at the run's output
// rows: the world poses of the scene's bodies, the logged signals (for the
// viewer's plot), and new geometry of shapes whose identifiers a control
// script changed.
//
// Frames are kept at least `frame_spacing` seconds apart (the display needs
// no more: the viewer interpolates between frames), and the run's last row is
// always the last frame. A frame holds, per scene body, its position and its
// orientation as a unit quaternion (x y z, qx qy qz qw) in float32: 28 bytes
// per body. The logged signals are kept at every row, not per frame
// (graphics/signal_track.h: a long run's as the extremes of each bin of
// time), so the plot shows the peaks the results hold.
//
// A shape naming identifiers is read again (ShapeBuilder::Read) when their
// values differ from those of its last version, at most once per
// `shape_spacing` seconds: each version is its tessellation at that time.
// Past `max_frames` frames (`max_version_bytes` of versions) every other one
// is dropped and the spacing doubled.
//
// Poses come from the mechanism's kinematics at the row's state (and the
// drives' values among the signals), computed in a workspace of its own.

#include <memory>
#include <string>
#include <vector>

#include "blocks/solver/simulator.h"
#include "graphics/mesh.h"
#include "graphics/scene.h"
#include "graphics/signal_track.h"
#include "mech/mechanism.h"

namespace mechflow::graphics {

struct RecorderOptions {
  double frame_spacing = 1.0 / 120;
  double shape_spacing = 1.0 / 15;
  // Bounds for long runs: past them every other frame (version) is dropped
  // and the spacing doubles, so memory and the file stay bounded whatever
  // t_end is.
  std::size_t max_frames = 100000;
  std::size_t max_version_bytes = std::size_t{32} << 20;
  // points of the plot's signals: past this many rows, bins of extremes
  std::size_t max_plot_points = SignalTrack::kMaxPoints;
};

// A shape's geometry from time t on.
struct ShapeVersion {
  int shape = 0;
  double t = 0.0;
  Mesh mesh;
};

class AnimationRecorder final : public blocks::RowObserver {
 public:
  // `columns` name the logged signals `logged` (time excluded).
  AnimationRecorder(const diagrams::LoadedDiagram& loaded, const Scene& scene, std::vector<std::string> columns,
                    RecorderOptions options = {});

  void OnRow(double t, const double* x, const blocks::Context& ctx) override;

  const std::vector<double>& times() const { return times_; }
  const std::vector<float>& poses() const { return poses_; }  // frame-major, 7 per body
  int num_bodies() const { return static_cast<int>(bodies_.size()); }
  const std::vector<std::string>& columns() const { return columns_; }
  const SignalTrack& signals() const { return signals_; }  // the logged columns at the rows
  const std::vector<ShapeVersion>& versions() const { return versions_; }  // by time

  // Shapes that could not be read again at a script's new identifier values
  // (they keep their last geometry), for the run's report.
  const std::vector<std::string>& warnings() const { return warnings_; }

  // The world pose of scene body `b` (-1: the ground) in frame `f`.
  mech::Pose Pose(int f, int b) const;

 private:
  struct Source {
    int block = -1;
    const mech::Mechanism* mechanism = nullptr;
    std::unique_ptr<mech::MechanismWorkspace> ws;
  };
  // a shape that follows identifiers: the values of its last version
  struct Follower {
    int shape = 0;
    std::vector<double> values;
    double t = 0.0;
  };
  void RecordShapeChanges(double t);
  void HalveFrames();
  void HalveVersions();

  const diagrams::LoadedDiagram& loaded_;
  const Scene& scene_;
  RecorderOptions options_;
  std::vector<SceneBody> bodies_;
  std::vector<Source> sources_;
  std::vector<int> source_of_body_;
  std::vector<std::string> columns_;
  std::vector<Follower> followers_;
  std::vector<double> times_;
  std::vector<float> poses_;
  SignalTrack signals_;
  std::vector<double> row_;  // the logged values of the row at hand
  std::vector<ShapeVersion> versions_;
  std::size_t version_bytes_ = 0;
  std::vector<std::string> warnings_;
};

}  // namespace mechflow::graphics
