#pragma once
// Scene: what the bodies of a diagram look like, read from the <shape>
// elements of its mechanisms (diagrams/FORMAT.md, "Shapes (graphics)").
//
// A shape hangs on a body (or on Base0, the ground) at a pose in the body
// frame and has no mass: the inertia stays as the <body> gives it. Solids
// (box, sphere, ellipsoid, cylinder, cone, plane, gear, surface), lines
// (polyline, circle, curve) and springs between two bodies. Every number is
// an expression of identifiers; a shape whose numbers name identifiers that
// a control script changes during the run follows them (ShapeBuilder::Read
// again at the new values: the Molecule's surface). Bad geometry (a radius
// <= 0, a zero axis, an unknown body) is an InputError naming file:line.

#include <memory>
#include <string>
#include <vector>

#include "diagrams/loader.h"
#include "mech/spatial.h"

namespace mechflow::graphics {

using mech::Mat3;
using mech::Vec3;

// A body that carries shapes: the mechanism block and the body in its model.
struct SceneBody {
  std::string label;  // "mechanism.body"
  int block = -1;     // in the diagram
  int body = -1;      // in the block's mech::Model
};

// A parametric curve x(u) or surface x(u, v), sampled at load or when an
// identifier it names changes.
struct Parametric {
  std::vector<Vec3> points;  // (samples_u + 1) x (samples_v + 1), u fastest; a curve has samples_v = 0
  int samples_u = 0, samples_v = 0;
};

struct Shape {
  std::string kind;  // one of ShapeKinds()
  std::string name;  // shown on hover; default kind + number
  int body = -1;     // index into Scene::bodies; -1: the ground
  Vec3 position = Vec3::Zero();
  Mat3 rotation = Mat3::Identity();  // shape axes in the body frame (from Cardan 1-2-3 angles)
  Vec3 size = Vec3::Ones();          // box edges; ellipsoid radii; plane edges (x, y)
  double radius = 0.0;               // sphere, cylinder, cone (base), circle, gear (pitch), spring
  double radius2 = 0.0;              // cone: the top's radius (0: a point)
  double length = 0.0;               // cylinder, cone; gear width
  Vec3 axis = Vec3::UnitZ();         // cylinder, cone, gear: unit, in the shape frame
  double tooth_height = 0.0;         // gear
  int teeth = 0;                     // gear
  double taper = 1.0;                // gear: radius at the +axis face over that at the -axis face
  std::vector<Vec3> points;          // polyline
  Parametric parametric;             // curve, surface
  int body2 = -1;                    // spring: second body (-1 ground)
  Vec3 point1 = Vec3::Zero(), point2 = Vec3::Zero();  // spring, in body / body2 frames
  int coils = 8;                     // spring
  std::string color = "#8899aa";
  double opacity = 1.0;
  std::string origin;                // file:line
  std::vector<int> identifiers;      // indices of the identifiers its numbers name
};

const std::vector<std::string>& ShapeKinds();

// Reads shapes from their <shape> elements; kept for the run, so a shape can
// be read again when identifiers it names change.
class ShapeBuilder {
 public:
  explicit ShapeBuilder(const diagrams::LoadedDiagram& loaded) : loaded_(loaded) {}
  // The shape of `element` (a <shape> of the mechanism element `mechanism`),
  // with `bodies` extended by the bodies it hangs on.
  Shape Read(const diagrams::ElementDesc& mechanism, const diagrams::ElementDesc& element, int number,
             std::vector<SceneBody>* bodies) const;

 private:
  const diagrams::LoadedDiagram& loaded_;
};

struct Scene {
  std::vector<SceneBody> bodies;
  std::vector<Shape> shapes;
  // where each shape was read from, to read it again (ShapeBuilder::Read)
  struct Source {
    const diagrams::ElementDesc* mechanism = nullptr;
    const diagrams::ElementDesc* element = nullptr;
    int number = 0;
  };
  std::vector<Source> sources;
  bool empty() const { return shapes.empty(); }
};

// The scene of every <shape> in the loaded diagram's mechanisms.
Scene BuildScene(const diagrams::LoadedDiagram& loaded);

}  // namespace mechflow::graphics
