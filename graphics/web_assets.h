#pragma once
// The viewer's scripts, embedded at build time (graphics/embed_assets.cmake).

namespace mechflow::graphics {

extern const char* const kThreeJs;           // three.js, build/three.min.js (MIT)
extern const char* const kOrbitControlsJs;   // three.js examples/js/controls/OrbitControls.js
extern const char* const kViewerJs;          // graphics/web/viewer.js

}  // namespace mechflow::graphics
