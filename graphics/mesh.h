#pragma once
// Mesh: a shape as triangles or as a line, in its body's frame (the shape's
// position and rotation applied), for the HTML viewer and the glTF file
// alike, so both show the same geometry.
//
// A spring is the exception: a helix of unit length along +y about the
// origin, which the viewer (and the glTF animation) turns, places and
// stretches onto its two points at every frame (SpringTransform).

#include <cstdint>
#include <vector>

#include "graphics/scene.h"

namespace mechflow::graphics {

struct Mesh {
  enum class Primitive { kTriangles, kLineStrip };  // glTF modes 4 and 3
  Primitive primitive = Primitive::kTriangles;
  std::vector<float> positions;        // x y z per vertex
  std::vector<std::uint32_t> indices;  // three per triangle; none for a line strip
  bool double_sided = false;           // plane and surface: both sides are seen
  int num_vertices() const { return static_cast<int>(positions.size() / 3); }
};

Mesh Tessellate(const Shape& shape);

// Area-weighted vertex normals of a triangle mesh, three per vertex, unit
// (+z where the triangles around a vertex have no area or cancel out).
std::vector<float> VertexNormals(const Mesh& mesh);

// Where a spring's unit helix goes: origin at point1 in the world, +y scaled
// by the length to point2. `from`, `to` are the world poses of the bodies.
struct SpringTransform {
  Vec3 translation;
  Eigen::Quaterniond rotation;
  double length;
};
SpringTransform PlaceSpring(const Shape& spring, const mech::Pose& from, const mech::Pose& to);

}  // namespace mechflow::graphics
