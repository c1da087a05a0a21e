#pragma once
// PoseRecorder: the world poses of a scene's bodies at the run's output
// rows, for the animation.
//
// Frames are kept at least `min_spacing` seconds apart (the display needs no
// more: the viewer interpolates between frames), and the run's last row is
// always the last frame. A frame holds, per scene body, its position and its
// orientation as a unit quaternion (x y z, qx qy qz qw), in float32: 28
// bytes per body and frame.
//
// The poses come from the mechanism's kinematics at the row's state (and the
// drives' values among the signals), computed in a workspace of its own.

#include <memory>
#include <vector>

#include "blocks/simulator.h"
#include "graphics/scene.h"
#include "mech/mechanism.h"

namespace mechflow::graphics {

class PoseRecorder final : public blocks::RowObserver {
 public:
  PoseRecorder(const blocks::Diagram& diagram, const Scene& scene, double min_spacing);

  void OnRow(double t, const double* x, const blocks::Context& ctx) override;

  const std::vector<double>& times() const { return times_; }
  const std::vector<float>& poses() const { return poses_; }  // frame-major, 7 per body
  int num_bodies() const { return static_cast<int>(bodies_.size()); }

 private:
  struct Source {
    int block = -1;
    const mech::Mechanism* mechanism = nullptr;
    std::unique_ptr<mech::MechanismWorkspace> ws;
  };
  const blocks::Diagram& diagram_;
  std::vector<SceneBody> bodies_;
  std::vector<Source> sources_;
  std::vector<int> source_of_body_;
  double min_spacing_;
  std::vector<double> times_;
  std::vector<float> poses_;
};

}  // namespace mechflow::graphics
