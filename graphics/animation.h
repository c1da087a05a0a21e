#pragma once
// The animation file: one self-contained HTML page (three.js and the viewer
// inlined, no network access when it is opened) with the scene and the
// recorded body poses. Controls: play/pause, speed, loop, a time slider and
// the clock, orbit/pan/zoom with the mouse, reset view.

#include <string>

#include "graphics/pose_recorder.h"
#include "graphics/scene.h"

namespace mechflow::graphics {

std::string AnimationHtml(const Scene& scene, const PoseRecorder& recording, const std::string& title);

}  // namespace mechflow::graphics
