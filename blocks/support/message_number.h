#pragma once
// Numbers as messages and printed tables show them.

#include <cstdio>
#include <string>

namespace mechflow::blocks {

// Ten significant digits ("%.10g"): enough to tell values apart, without
// round-off noise.
inline std::string MessageNumber(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.10g", v);
  return text;
}

// `value` in printf's `format` (one double conversion such as "%8.3f"); -0
// shows as 0.
inline std::string Formatted(const char* format, double value) {
  char text[64];
  std::snprintf(text, sizeof text, format, value == 0.0 ? 0.0 : value);
  return text;
}

}  // namespace mechflow::blocks
