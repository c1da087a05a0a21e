#include "graphics/animation.h"

#include <sstream>

#include "blocks/outputs/csv.h"
#include "graphics/encoding.h"
#include "graphics/mesh.h"
#include "graphics/web_assets.h"

namespace mechflow::graphics {
namespace {

template <typename T>
std::string Base64Of(const std::vector<T>& values) {
  return "\"" + Base64(values.data(), values.size() * sizeof(T)) + "\"";
}

}  // namespace

// The HTML parser reads a <script> before JavaScript does: "</script" ends
// it and "<!--" with "<script" hides the rest of the page. JSON has these
// characters only inside strings, where \u escapes mean the same to
// JavaScript; U+2028 and U+2029 ended string literals before ES2019.
std::string ScriptSafeJson(const std::string& json) {
  std::string out;
  out.reserve(json.size());
  for (std::size_t i = 0; i < json.size(); ++i) {
    const char c = json[i];
    if (c == '<') out += "\\u003c";
    else if (c == '>') out += "\\u003e";
    else if (c == '&') out += "\\u0026";
    else if (c == '\xE2' && json.compare(i + 1, 2, "\x80\xA8") == 0) out += "\\u2028", i += 2;
    else if (c == '\xE2' && json.compare(i + 1, 2, "\x80\xA9") == 0) out += "\\u2029", i += 2;
    else out += c;
  }
  return out;
}

namespace {

std::string Escaped(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '&') out += "&amp;";
    else out += c;
  }
  return out;
}

std::string Json(const Vec3& v) {
  return "[" + blocks::CsvNumber(v.x()) + "," + blocks::CsvNumber(v.y()) + "," + blocks::CsvNumber(v.z()) + "]";
}

// The viewer's data: MECHFLOW_DATA (graphics/web/viewer.js says what it holds).
std::string DataJson(const Scene& scene, const AnimationRecorder& recording, const std::string& title) {
  static_assert(sizeof(float) == 4 && sizeof(double) == 8, "float32 and float64 arrays");
  std::ostringstream o;
  o << "{\"title\":" << Quoted(title) << ",\"bodies\":[";
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) o << (i ? "," : "") << Quoted(scene.bodies[i].label);
  o << "],\"shapes\":[";
  for (std::size_t i = 0; i < scene.shapes.size(); ++i) {
    const Shape& s = scene.shapes[i];
    const Mesh mesh = Tessellate(s);
    o << (i ? "," : "") << "{\"kind\":" << Quoted(s.kind) << ",\"name\":" << Quoted(s.name) << ",\"body\":" << s.body
      << ",\"color\":" << Quoted(s.color) << ",\"opacity\":" << blocks::CsvNumber(s.opacity)
      << ",\"line\":" << (mesh.primitive == Mesh::Primitive::kLineStrip ? "true" : "false")
      << ",\"doubleSided\":" << (mesh.double_sided ? "true" : "false") << ",\"positions\":" << Base64Of(mesh.positions)
      << ",\"indices\":" << Base64Of(mesh.indices);
    if (s.kind == "spring")
      o << ",\"body2\":" << s.body2 << ",\"point1\":" << Json(s.point1) << ",\"point2\":" << Json(s.point2);
    o << "}";
  }
  o << "],\"versions\":[";
  for (std::size_t i = 0; i < recording.versions().size(); ++i) {
    const ShapeVersion& v = recording.versions()[i];
    o << (i ? "," : "") << "{\"shape\":" << v.shape << ",\"t\":" << blocks::CsvNumber(v.t)
      << ",\"positions\":" << Base64Of(v.mesh.positions) << "}";
  }
  o << "],\"times\":[";
  for (std::size_t i = 0; i < recording.times().size(); ++i) o << (i ? "," : "") << blocks::CsvNumber(recording.times()[i]);
  o << "],\"poses\":" << Base64Of(recording.poses()) << ",\"columns\":[";
  for (std::size_t i = 0; i < recording.columns().size(); ++i) o << (i ? "," : "") << Quoted(recording.columns()[i]);
  o << "],\"plot\":{\"times\":" << Base64Of(recording.signals().Times())
    << ",\"values\":" << Base64Of(recording.signals().Values())
    << ",\"binned\":" << (recording.signals().binned() ? "true" : "false") << "}}";
  return o.str();
}

}  // namespace

std::string AnimationHtml(const Scene& scene, const AnimationRecorder& recording, const std::string& title) {
  std::ostringstream html;
  html << "<!doctype html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" << Escaped(title)
       << "</title>\n<style>\n"
          "html, body { margin: 0; height: 100%; font: 14px sans-serif; overflow: hidden; }\n"
          "#view { position: absolute; top: 0; bottom: 44px; left: 0; right: 0; }\n"
          "#view canvas { width: 100%; height: 100%; display: block; }\n"
          "#bar { position: absolute; bottom: 0; left: 0; right: 0; height: 44px; display: flex; gap: 10px;"
          " align-items: center; padding: 0 10px; background: #e4e4e8; }\n"
          "#time { flex: 1; min-width: 60px; }\n#bar label, #clock { white-space: nowrap; }\n#bar select { max-width: 7em; }\n#title { position: absolute; top: 8px; left: 10px; color: #333; }\n"
          "#hover { position: absolute; pointer-events: none; background: #fffff0; border: 1px solid #999;"
          " padding: 2px 5px; display: none; }\n"
          "#plot { position: absolute; right: 10px; bottom: 54px; width: 320px; height: 150px;"
          " background: rgba(255,255,255,0.85); border: 1px solid #bbb; display: none; }\n"
          "#mechflow-test { display: none; }\n"
          "</style>\n</head>\n<body>\n<div id=\"view\"></div>\n<div id=\"title\"></div>\n<div id=\"hover\"></div>\n"
          "<canvas id=\"plot\" width=\"320\" height=\"150\"></canvas>\n"
          "<div id=\"bar\"><button id=\"play\">play</button>"
          "<label>speed <select id=\"speed\"><option>0.1</option><option>0.25</option><option>0.5</option>"
          "<option selected>1</option><option>2</option></select></label>"
          "<label><input type=\"checkbox\" id=\"loop\" checked> loop</label>"
          "<input type=\"range\" id=\"time\" min=\"0\" max=\"1000\" value=\"0\"><span id=\"clock\"></span>"
          "<label>trace <select id=\"trace\"><option value=\"\">none</option></select></label>"
          "<label>plot <select id=\"signal\"><option value=\"\">none</option></select></label>"
          "<button id=\"reset\">reset view</button></div>\n<pre id=\"mechflow-test\"></pre>\n"
       << "<script>\n" << kThreeJs << "\n</script>\n<script>\n" << kOrbitControlsJs << "\n</script>\n"
       << "<script>\nconst MECHFLOW_DATA = " << ScriptSafeJson(DataJson(scene, recording, title)) << ";\n</script>\n"
       << "<script>\n" << kViewerJs << "\n</script>\n</body>\n</html>\n";
  return html.str();
}

}  // namespace mechflow::graphics
