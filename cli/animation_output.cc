#include "cli/animation_output.h"

#include "graphics/animation.h"
#include "graphics/gltf.h"
#include "graphics/size_estimate.h"
#include "mech/errors.h"

namespace mechflow::cli {

AnimationOutput::AnimationOutput(const diagrams::LoadedDiagram& loaded, const Arguments& args, blocks::Simulator* sim)
    : loaded_(loaded), scene_(graphics::BuildScene(loaded)) {
  const std::string& name = loaded.description.name;
  html_ = !loaded.animation_file.empty() ? loaded.animation_file : args.animate ? name + ".html" : "";
  glb_ = !loaded.gltf_file.empty() ? loaded.gltf_file : args.gltf ? name + ".glb" : "";
  if (args.no_animate) html_.clear(), glb_.clear();
  if (html_.empty() && glb_.empty()) return;
  if (scene_.empty())
    throw InputError(args.file + ": nothing to animate: no <shape> on any body; give the bodies shapes "
                                 "(diagrams/FORMAT.md, Shapes)");
  const std::vector<std::string>& columns = sim->results().columns();  // time first
  recording_ = std::make_unique<graphics::AnimationRecorder>(
      loaded, scene_, std::vector<std::string>(columns.begin() + 1, columns.end()));
  sim->SetRowObserver(recording_.get());
}

bool AnimationOutput::Write(const OutputFolder& folder, std::ostream& out, std::ostream& err) const {
  if (!recording_) return true;
  for (const std::string& warning : recording_->warnings())
    err << "warning: a shape keeps its last geometry " << warning << "\n";
  bool written = true;
  const auto write = [&](const std::string& file, const std::string& bytes, std::size_t frames,
                         const std::string& note) {
    try {
      folder.Write(file, bytes);
      out << "wrote " << folder.PathOf(file) << " (" << frames << " frames of " << recording_->num_bodies()
          << " bodies, " << bytes.size() / 1024 << " KiB" << note << ")\n";
    } catch (const WriteError& e) {
      err << e.what() << "\n";
      written = false;
    }
  };
  const std::string& title = loaded_.description.name;
  if (!html_.empty()) write(html_, graphics::AnimationHtml(scene_, *recording_, title), recording_->times().size(), "");
  if (glb_.empty()) return written;
  try {
    const graphics::Gltf gltf = graphics::GltfBinary(scene_, *recording_, title);
    write(glb_, gltf.bytes, gltf.frames,
          gltf.merged ? "; " + std::to_string(gltf.merged) + (gltf.merged == 1 ? " frame" : " frames") +
                            " merged into the next: float32 times cannot tell them apart this long after the start"
                      : "");
  } catch (const graphics::GltfRefused& e) {  // the other files are written; the run reports the missing one
    err << "no glTF file " << folder.PathOf(glb_) << ": " << e.what() << "\n";
    written = false;
  }
  return written;
}

std::vector<OutputEstimate> AnimationOutput::EstimateSizes(double rows) const {
  if (!recording_) return {};
  const graphics::AnimationSizeEstimate e = graphics::EstimateAnimationSize(
      scene_, loaded_.solver.t_start, loaded_.solver.t_end, rows, static_cast<int>(recording_->columns().size()));
  const std::string reckoning = std::to_string(static_cast<long long>(e.frames)) + " frames x " +
                                std::to_string(scene_.bodies.size()) + " bodies, and " +
                                ByteSizeText(e.mesh_bytes) + " of shapes";
  // the page's plot: every logged column at the rows (at most 4096 points)
  const std::string plot = ", a plot of " + std::to_string(static_cast<long long>(e.plot_points)) + " points x " +
                           std::to_string(recording_->columns().size() + 1) + " numbers";
  const std::string advice =
      "give fewer bodies shapes, coarser shapes, or a shorter t_end; leave the animation out with --no-animate; "
      "or raise the budget with --max-output 8G";
  std::vector<OutputEstimate> files;
  if (!html_.empty()) files.push_back({html_, e.html_bytes, 0.0, reckoning + plot, advice});
  if (!glb_.empty()) files.push_back({glb_, e.glb_bytes, 0.0, reckoning, advice});
  return files;
}

std::vector<OutputStem> AnimationOutput::Stems() const {
  std::vector<OutputStem> stems;
  const auto add = [&](const std::string& file, const std::string& named, const char* attribute, const char* option) {
    if (file.empty()) return;
    stems.push_back({StemOf(file), !named.empty() ? std::string("<output ") + attribute + "=\"" + file + "\">"
                                                  : std::string(option) + " (the diagram's name \"" +
                                                        loaded_.description.name + "\")"});
  };
  add(html_, loaded_.animation_file, "animation", "--animate");
  add(glb_, loaded_.gltf_file, "gltf", "--gltf");
  return stems;
}

}  // namespace mechflow::cli
