#pragma once
// The scene and its motion as a glTF 2.0 binary (.glb), for Blender and
// other viewers.
//
// Below a root node: the ground's shapes (node "Base0", when there are
// any), one node per moving body holding a mesh with a primitive per shape
// (the same tessellation as the HTML viewer: graphics/mesh.h), and a node
// per spring, in this order. One animation
// "motion" moves them: translation and rotation of every body, and
// translation, rotation and scale of every spring's unit helix, at the
// recorded frames (LINEAR). glTF's y is up; a root node turns mechflow's
// z-up world onto it (-90 degrees about x), so every node below it keeps
// mechflow's coordinates.
//
// Shapes that change with identifiers (ShapeVersion) keep their geometry at
// the start: glTF could morph them only between fixed targets.
//
// Every number is float32, the format's only real type. Keyframe times are
// seconds from the first frame (glTF's clock starts with the animation), so
// a run starting late keeps its resolution; frames float32 cannot tell apart
// from the next one at their time (a long run) merge into it, so the times
// strictly increase as the format requires.

#include <stdexcept>
#include <string>

#include "graphics/recorder.h"
#include "graphics/scene.h"

namespace mechflow::graphics {

// Why a run has no glTF file: a vertex, position or time that float32
// cannot hold (beyond +-3.4e38), naming the shape, body or time and what to do.
class GltfRefused : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Gltf {
  std::string bytes;  // the .glb
  int frames = 0;     // keyframes written
  int merged = 0;     // recorded frames merged into the next (their times equal in float32)
};

// Throws GltfRefused.
Gltf GltfBinary(const Scene& scene, const AnimationRecorder& recording, const std::string& title);

}  // namespace mechflow::graphics
