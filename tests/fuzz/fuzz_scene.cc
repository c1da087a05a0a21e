// Fuzz target: the shapes of a diagram's mechanisms -- a diagram's XML text
// loaded as for a run, its <shape>s read into a scene (expressions of
// identifiers, poses, parametric curves and surfaces) and every shape
// tessellated with its vertex normals, as the animation and glTF writers do.

#include "diagrams/loader.h"
#include "diagrams/xml_reader.h"
#include "graphics/mesh.h"
#include "graphics/scene.h"
#include "tests/fuzz/fuzz_target.h"

namespace {

void BuildAndTessellate(const std::string& text) {
  using namespace mechflow;
  const diagrams::LoadedDiagram loaded =
      diagrams::LoadDiagramDescription(diagrams::ReadDiagramText(text, "fuzz.xml"));
  const graphics::Scene scene = graphics::BuildScene(loaded);
  for (const graphics::Shape& shape : scene.shapes) {
    const graphics::Mesh mesh = graphics::Tessellate(shape);
    graphics::VertexNormals(mesh);
  }
}

}  // namespace

MECHFLOW_FUZZ_TARGET(BuildAndTessellate)
