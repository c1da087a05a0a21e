#include "graphics/recorder.h"

#include <algorithm>
#include <limits>

#include <Eigen/Geometry>

#include "blocks/library/mechanism_block.h"
#include "mech/errors.h"

namespace mechflow::graphics {

AnimationRecorder::AnimationRecorder(const diagrams::LoadedDiagram& loaded, const Scene& scene,
                                     std::vector<std::string> columns, RecorderOptions options)
    : loaded_(loaded),
      scene_(scene),
      options_(options),
      bodies_(scene.bodies),
      columns_(std::move(columns)),
      signals_(columns_.size(), loaded.solver.t_start, loaded.solver.t_end - loaded.solver.t_start,
               options.max_plot_points),
      row_(columns_.size()) {
  const blocks::Diagram& diagram = *loaded.diagram;
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
  for (std::size_t i = 0; i < scene.shapes.size(); ++i)
    if (!scene.shapes[i].identifiers.empty()) {
      Follower f{static_cast<int>(i), {}, -std::numeric_limits<double>::infinity()};
      for (const int id : scene.shapes[i].identifiers) f.values.push_back(loaded.identifiers->value(id));
      followers_.push_back(std::move(f));
    }
}

void AnimationRecorder::OnRow(double t, const double* x, const blocks::Context& ctx) {
  // the last frame is tentative while it lies within frame_spacing of the one
  // before: a new row takes its place
  const std::size_t n = times_.size();
  if (n >= 2 && times_[n - 1] - times_[n - 2] < options_.frame_spacing) {
    times_.back() = t;
    poses_.resize(poses_.size() - 7 * bodies_.size());
  } else {
    if (times_.size() >= options_.max_frames) HalveFrames();
    times_.push_back(t);
  }
  const blocks::Diagram& diagram = *loaded_.diagram;
  for (Source& s : sources_) {
    const blocks::BlockLayout& layout = diagram.layout(s.block);
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
  std::size_t c = 0;
  for (const blocks::SignalRef& s : loaded_.logged)
    for (int i = 0; i < s.width && c < row_.size(); ++i) row_[c++] = ctx.signals[s.offset + i];
  signals_.Add(t, row_.data());
  RecordShapeChanges(t);
}

void AnimationRecorder::RecordShapeChanges(double t) {
  for (Follower& f : followers_) {
    if (t - f.t < options_.shape_spacing) continue;
    const Shape& shape = scene_.shapes[f.shape];
    bool changed = false;
    for (std::size_t k = 0; k < shape.identifiers.size(); ++k) {
      const double value = loaded_.identifiers->value(shape.identifiers[k]);
      changed = changed || value != f.values[k];
      f.values[k] = value;
    }
    if (!changed) continue;
    const Scene::Source& source = scene_.sources[f.shape];
    std::vector<SceneBody> bodies = scene_.bodies;  // unchanged: the shape hangs where it did
    f.t = t;
    try {
      versions_.push_back(
          {f.shape, t, Tessellate(ShapeBuilder(loaded_).Read(*source.mechanism, *source.element, source.number, &bodies))});
      version_bytes_ += versions_.back().mesh.positions.size() * sizeof(float);
      if (version_bytes_ > options_.max_version_bytes) HalveVersions();
    } catch (const InputError& e) {  // the run goes on; the shape keeps its last geometry
      if (warnings_.size() < 10) warnings_.push_back("at t = " + std::to_string(t) + " s: " + e.what());
    }
  }
}

void AnimationRecorder::HalveFrames() {
  const std::size_t nb = 7 * bodies_.size();
  std::size_t kept = 0;
  for (std::size_t f = 0; f < times_.size(); f += 2, ++kept) {
    times_[kept] = times_[f];
    std::copy_n(poses_.begin() + f * nb, nb, poses_.begin() + kept * nb);
  }
  times_.resize(kept);
  poses_.resize(kept * nb);
  options_.frame_spacing *= 2;
}

void AnimationRecorder::HalveVersions() {
  std::vector<ShapeVersion> kept;
  std::vector<int> seen(scene_.shapes.size(), 0);  // each shape keeps its 1st, 3rd, ... version
  version_bytes_ = 0;
  for (ShapeVersion& v : versions_)
    if (seen[v.shape]++ % 2 == 0) {
      version_bytes_ += v.mesh.positions.size() * sizeof(float);
      kept.push_back(std::move(v));
    }
  versions_ = std::move(kept);
  options_.shape_spacing *= 2;
}

mech::Pose AnimationRecorder::Pose(int f, int b) const {
  if (b < 0) return {};
  const float* p = &poses_[7 * (static_cast<std::size_t>(f) * bodies_.size() + b)];
  const Eigen::Quaterniond q(p[6], p[3], p[4], p[5]);
  return {q.normalized().toRotationMatrix(), Vec3(p[0], p[1], p[2])};
}

}  // namespace mechflow::graphics
