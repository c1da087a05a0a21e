#pragma once
// The animation files of one `mechflow run`: NAME.html (<output
// animation>, --animate) and NAME.glb (<output gltf>, --gltf), from the
// shapes of the diagram and what an AnimationRecorder saw during the run.

#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "blocks/solver/simulator.h"
#include "cli/arguments.h"
#include "cli/output_claims.h"
#include "cli/output_budget.h"
#include "cli/output_folder.h"
#include "diagrams/loader.h"
#include "graphics/recorder.h"
#include "graphics/scene.h"

namespace mechflow::cli {

class AnimationOutput {
 public:
  // Reads the shapes (bad geometry is bad input, before the run) and, when
  // an animation file is asked for, records the run. Refuses (InputError)
  // an animation of a diagram without shapes.
  AnimationOutput(const diagrams::LoadedDiagram& loaded, const Arguments& args, blocks::Simulator* sim);

  // Writes the files, saying each on `out`; false when one could not be
  // written or a glTF file cannot hold the run (graphics::GltfRefused), said
  // on `err`: the run then exits 1 with its other files written.
  bool Write(const OutputFolder& folder, std::ostream& out, std::ostream& err) const;

  // The size of each file it will write, for a run of `rows` rows (the
  // output budget, cli/output_budget.h).
  std::vector<OutputEstimate> EstimateSizes(double rows) const;

  // The stems of the files it will write (cli/output_claims.h).
  std::vector<OutputStem> Stems() const;

 private:
  const diagrams::LoadedDiagram& loaded_;
  graphics::Scene scene_;
  std::string html_, glb_;
  std::unique_ptr<graphics::AnimationRecorder> recording_;
};

}  // namespace mechflow::cli
