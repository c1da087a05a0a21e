#pragma once
// Scene: what the bodies of a diagram look like, read from the <shape>
// elements of its mechanisms.
//
// A shape hangs on a body (or on Base0, the ground) at a pose in the body
// frame and has no mass: the inertia stays as the <body> gives it. Kinds:
//   box       size "a b c" (edge lengths along the shape's x, y, z)
//   sphere    radius
//   cylinder  radius, length, axis (default "0 0 1"), centred on its position
//   polyline  points "x y z; x y z; ..." (at least two; a guide, a path)
//   spring    from point1 on body to point2 on body2: a helix of `coils`
//             turns and `radius` whose length follows the two points
// with color ("#rrggbb") and opacity (0..1). Every number is an expression
// of identifiers, evaluated at load. Bad geometry (a radius <= 0, a zero
// axis, an unknown body) is an InputError naming file:line.

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

struct Shape {
  std::string kind;  // box, sphere, cylinder, polyline, spring
  std::string name;  // shown on hover; default kind + number
  int body = -1;     // index into Scene::bodies; -1: the ground
  Vec3 position = Vec3::Zero();
  Mat3 rotation = Mat3::Identity();  // shape axes in the body frame (Cardan 1-2-3 angles given)
  Vec3 size = Vec3::Ones();          // box
  double radius = 0.0;               // sphere, cylinder, spring
  double length = 0.0;               // cylinder
  Vec3 axis = Vec3::UnitZ();         // cylinder, unit
  std::vector<Vec3> points;          // polyline
  int body2 = -1;                    // spring: second body (-1 ground)
  Vec3 point1 = Vec3::Zero(), point2 = Vec3::Zero();  // spring, in body / body2 frames
  int coils = 8;                     // spring
  std::string color = "#8899aa";
  double opacity = 1.0;
  std::string origin;                // file:line
};

struct Scene {
  std::vector<SceneBody> bodies;
  std::vector<Shape> shapes;
  bool empty() const { return shapes.empty(); }
};

// The scene of every <shape> in the loaded diagram's mechanisms.
Scene BuildScene(const diagrams::LoadedDiagram& loaded);

// The scene as JSON for the viewer (graphics/web/viewer.js).
std::string SceneJson(const Scene& scene, const std::string& title);

}  // namespace mechflow::graphics
