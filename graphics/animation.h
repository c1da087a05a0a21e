#pragma once
// The animation file: one self-contained HTML page (three.js and the viewer
// inlined, no network access when it is opened) with the scene's meshes, the
// recorded body poses, the shapes' later versions and the logged signals.
// Controls: play/pause, speed, loop, a time slider and the clock,
// orbit/pan/zoom with the mouse, reset view, names on hover, the path of a
// chosen point, a plot of a chosen signal with a cursor at the time shown.

#include <string>

#include "graphics/recorder.h"
#include "graphics/scene.h"

namespace mechflow::graphics {

std::string AnimationHtml(const Scene& scene, const AnimationRecorder& recording, const std::string& title);

// JSON text as the page embeds it in a <script>: '<', '>', '&', U+2028 and
// U+2029 as \u escapes, so no name in it can end or hide the element.
std::string ScriptSafeJson(const std::string& json);

}  // namespace mechflow::graphics
