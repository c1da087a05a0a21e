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

#include <string>

#include "graphics/recorder.h"
#include "graphics/scene.h"

namespace mechflow::graphics {

std::string GltfBinary(const Scene& scene, const AnimationRecorder& recording, const std::string& title);

}  // namespace mechflow::graphics
