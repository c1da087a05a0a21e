#pragma once
// How large the animation files of a run will be, estimated before the run
// (the output budget of cli/output_budget.h): frames x bodies x bytes per
// pose, the logged signals per row (at most RecorderOptions::max_plot_points
// points), the shapes' meshes and, for the HTML page, the viewer's scripts.

#include "graphics/recorder.h"
#include "graphics/scene.h"

namespace mechflow::graphics {

struct AnimationSizeEstimate {
  double frames = 0.0;      // as the recorder keeps them (at most max_frames)
  double plot_points = 0.0; // the plot's points (rows, or two per bin of a long run)
  double mesh_bytes = 0.0;  // positions and indices of every shape, binary
  double html_bytes = 0.0;  // NAME.html
  double glb_bytes = 0.0;   // NAME.glb
};

// `rows`: the run's output rows; `columns`: its logged columns (time
// excluded), which the HTML page carries per row for its plot. Versions
// of shapes that follow identifiers are left out: the recorder bounds them
// (RecorderOptions::max_version_bytes).
AnimationSizeEstimate EstimateAnimationSize(const Scene& scene, double t_start, double t_end, double rows,
                                            int columns, const RecorderOptions& options = {});

}  // namespace mechflow::graphics
