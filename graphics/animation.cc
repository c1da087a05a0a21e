#include "graphics/animation.h"

#include <cstdint>
#include <cstring>
#include <sstream>

#include "blocks/csv.h"
#include "graphics/web_assets.h"

namespace mechflow::graphics {
namespace {

std::string Base64(const unsigned char* data, std::size_t size) {
  static const char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((size + 2) / 3 * 4);
  for (std::size_t i = 0; i < size; i += 3) {
    const std::uint32_t a = data[i], b = i + 1 < size ? data[i + 1] : 0, c = i + 2 < size ? data[i + 2] : 0;
    const std::uint32_t v = a << 16 | b << 8 | c;
    out += kDigits[v >> 18 & 63];
    out += kDigits[v >> 12 & 63];
    out += i + 1 < size ? kDigits[v >> 6 & 63] : '=';
    out += i + 2 < size ? kDigits[v & 63] : '=';
  }
  return out;
}

// JSON inside a <script>: "</" would end the element early.
std::string ScriptSafe(std::string json) {
  for (std::size_t i = 0; (i = json.find("</", i)) != std::string::npos; i += 3) json.replace(i, 2, "<\\/");
  return json;
}

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

}  // namespace

std::string AnimationHtml(const Scene& scene, const PoseRecorder& recording, const std::string& title) {
  std::ostringstream times;
  for (std::size_t i = 0; i < recording.times().size(); ++i)
    times << (i ? "," : "") << blocks::CsvNumber(recording.times()[i]);
  const std::vector<float>& poses = recording.poses();
  static_assert(sizeof(float) == 4, "poses are float32");
  const std::string data = Base64(reinterpret_cast<const unsigned char*>(poses.data()), poses.size() * sizeof(float));

  std::ostringstream html;
  html << "<!doctype html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" << Escaped(title)
       << "</title>\n<style>\n"
          "html, body { margin: 0; height: 100%; font: 14px sans-serif; }\n"
          "#view { position: absolute; top: 0; bottom: 44px; left: 0; right: 0; }\n"
          "#view canvas { width: 100%; height: 100%; display: block; }\n"
          "#bar { position: absolute; bottom: 0; left: 0; right: 0; height: 44px; display: flex; gap: 10px;"
          " align-items: center; padding: 0 10px; background: #e4e4e8; }\n"
          "#time { flex: 1; }\n#title { position: absolute; top: 8px; left: 10px; color: #333; }\n"
          "#mechflow-test { display: none; }\n"
          "</style>\n</head>\n<body>\n<div id=\"view\"></div>\n<div id=\"title\"></div>\n"
          "<div id=\"bar\"><button id=\"play\">play</button>"
          "<label>speed <select id=\"speed\"><option>0.1</option><option>0.25</option><option>0.5</option>"
          "<option selected>1</option><option>2</option></select></label>"
          "<label><input type=\"checkbox\" id=\"loop\" checked> loop</label>"
          "<input type=\"range\" id=\"time\" min=\"0\" max=\"1000\" value=\"0\"><span id=\"clock\"></span>"
          "<button id=\"reset\">reset view</button></div>\n<pre id=\"mechflow-test\"></pre>\n"
       << "<script>\n" << kThreeJs << "\n</script>\n<script>\n" << kOrbitControlsJs << "\n</script>\n"
       << "<script>\nconst MECHFLOW_SCENE = " << ScriptSafe(SceneJson(scene, title)) << ";\n"
       << "const MECHFLOW_POSES = {times: [" << times.str() << "], data: \"" << data << "\"};\n</script>\n"
       << "<script>\n" << kViewerJs << "\n</script>\n</body>\n</html>\n";
  return html.str();
}

}  // namespace mechflow::graphics
