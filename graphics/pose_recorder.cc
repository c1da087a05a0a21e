#include "graphics/pose_recorder.h"

#include <Eigen/Geometry>

#include "blocks/library/mechanism_block.h"

namespace mechflow::graphics {

PoseRecorder::PoseRecorder(const blocks::Diagram& diagram, const Scene& scene, double min_spacing)
    : diagram_(diagram), bodies_(scene.bodies), min_spacing_(min_spacing) {
  for (const SceneBody& body : bodies_) {
    int source = -1;
    for (std::size_t i = 0; i < sources_.size(); ++i)
      if (sources_[i].block == body.block) source = static_cast<int>(i);
    if (source < 0) {
      const auto& block = dynamic_cast<const blocks::MechanismBlock&>(diagram.block(body.block));
      sources_.push_back({body.block, &block.mechanism(), std::make_unique<mech::MechanismWorkspace>(block.mechanism())});
      source = static_cast<int>(sources_.size()) - 1;
    }
    source_of_body_.push_back(source);
  }
}

void PoseRecorder::OnRow(double t, const double* x, const blocks::Context& ctx) {
  // the last frame is tentative while it lies within min_spacing of the one
  // before: a new row takes its place
  const std::size_t n = times_.size();
  const bool replace = n >= 2 && times_[n - 1] - times_[n - 2] < min_spacing_;
  if (replace) {
    times_.back() = t;
    poses_.resize(poses_.size() - 7 * bodies_.size());
  } else {
    times_.push_back(t);
  }
  for (Source& s : sources_) {
    const blocks::BlockLayout& layout = diagram_.layout(s.block);
    // the drives' values, as the block reads them (its ports after the inputs)
    const int first_drive = s.mechanism->num_inputs();
    for (std::size_t k = 0; k < s.ws->kin.drives.size(); ++k) {
      const double* jet = &ctx.signals[layout.input_offset[first_drive + static_cast<int>(k)]];
      s.ws->kin.drives[k] = {jet[0], jet[1], jet[2]};
    }
    mech::EvaluatePositions(*s.mechanism, t, {x + layout.first_state, static_cast<std::size_t>(layout.num_states)},
                            s.ws.get());
  }
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    const mech::Pose& pose = sources_[source_of_body_[b]].ws->kin.body_pose[bodies_[b].body];
    const Eigen::Quaterniond q(pose.R);
    for (const double v : {pose.p.x(), pose.p.y(), pose.p.z(), q.x(), q.y(), q.z(), q.w()})
      poses_.push_back(static_cast<float>(v));
  }
}

}  // namespace mechflow::graphics
