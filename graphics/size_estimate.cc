#include "graphics/size_estimate.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "graphics/mesh.h"
#include "graphics/web_assets.h"

namespace mechflow::graphics {

AnimationSizeEstimate EstimateAnimationSize(const Scene& scene, double t_start, double t_end, double rows,
                                            int columns, const RecorderOptions& options) {
  AnimationSizeEstimate e;
  // frames at least frame_spacing apart, at most one per row; past
  // max_frames the recorder halves them
  e.frames = std::min({rows, std::floor((t_end - t_start) / options.frame_spacing) + 1.0,
                       static_cast<double>(options.max_frames)});
  double springs = 0.0, normals = 0.0;
  for (const Shape& s : scene.shapes) {
    const Mesh mesh = Tessellate(s);
    e.mesh_bytes += 4.0 * (mesh.positions.size() + mesh.indices.size());
    if (mesh.primitive == Mesh::Primitive::kTriangles) normals += 4.0 * mesh.positions.size();
    springs += s.kind == "spring";
  }
  const double bodies = static_cast<double>(scene.bodies.size());
  // the plot's points: every row, up to the SignalTrack's bound
  e.plot_points = std::min(rows, static_cast<double>(options.max_plot_points));
  // HTML: float32 poses (7 per body) in base64 (4/3), frame times as text
  // (about 20 characters each), the plot's float64 times and signals in
  // base64, the meshes in base64, the scripts
  const double scripts = static_cast<double>(std::strlen(kThreeJs) + std::strlen(kOrbitControlsJs) +
                                             std::strlen(kViewerJs));
  e.html_bytes = e.frames * (bodies * 28.0 * 4.0 / 3.0 + 20.0) + e.plot_points * (8.0 + columns * 8.0) * 4.0 / 3.0 +
                 e.mesh_bytes * 4.0 / 3.0 + scripts;
  // glTF: float32 times, a translation and a rotation per body (and a
  // scale per spring) per frame; meshes with their normals
  e.glb_bytes = e.frames * (4.0 + bodies * 28.0 + springs * 40.0) + e.mesh_bytes + normals;
  return e;
}

}  // namespace mechflow::graphics
