#include "graphics/gltf.h"

#include <cmath>
#include <cstdint>
#include <functional>
#include <sstream>

#include <Eigen/Geometry>

#include "blocks/outputs/csv.h"
#include "graphics/encoding.h"
#include "graphics/mesh.h"

namespace mechflow::graphics {
namespace {

constexpr int kFloat = 5126, kUnsignedInt = 5125;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;

std::string Number(double v) { return blocks::CsvNumber(v); }

// Names the owner of an accessor's element (a vertex, a frame) for a refusal.
using Where = std::function<std::string(std::size_t element)>;

// The binary chunk and the JSON of its bufferViews and accessors.
class Buffer {
 public:
  // An accessor of `count` elements of `type` ("SCALAR", "VEC3", ...) with
  // `components` floats each; min and max are given for POSITION and
  // animation inputs, which the format requires. Every float of the file
  // passes here: one that overflowed (or is NaN) refuses the file, naming
  // `where` it came from.
  int Floats(const std::vector<float>& values, int components, const char* type, int target, bool bounds,
             const Where& where) {
    for (std::size_t i = 0; i < values.size(); ++i)
      if (!std::isfinite(values[i]))
        throw GltfRefused(where(i / components) +
                          ": beyond float32's range (+-3.4e38), the glTF file's only number type; scale the model "
                          "(other units) or leave out --gltf (<output gltf>)");
    const int count = static_cast<int>(values.size()) / components;
    std::string extra;
    if (bounds) {
      std::vector<float> lo(components, INFINITY), hi(components, -INFINITY);
      for (std::size_t i = 0; i < values.size(); ++i) {
        lo[i % components] = std::min(lo[i % components], values[i]);
        hi[i % components] = std::max(hi[i % components], values[i]);
      }
      extra = ",\"min\":" + List(lo) + ",\"max\":" + List(hi);
    }
    return Accessor(values.data(), values.size() * 4, kFloat, count, type, target, extra);
  }
  int Indices(const std::vector<std::uint32_t>& values) {
    return Accessor(values.data(), values.size() * 4, kUnsignedInt, static_cast<int>(values.size()), "SCALAR",
                    kElementArrayBuffer, "");
  }
  const std::string& bytes() const { return bytes_; }
  std::string ViewsJson() const { return "[" + views_ + "]"; }
  std::string AccessorsJson() const { return "[" + accessors_ + "]"; }

 private:
  static std::string List(const std::vector<float>& v) {
    std::string s = "[";
    for (std::size_t i = 0; i < v.size(); ++i) s += (i ? "," : "") + Number(v[i]);
    return s + "]";
  }
  int Accessor(const void* data, std::size_t size, int component, int count, const char* type, int target,
               const std::string& extra) {
    const std::size_t offset = bytes_.size();
    bytes_.append(static_cast<const char*>(data), size);
    while (bytes_.size() % 4) bytes_ += '\0';
    const int view = num_++;
    views_ += std::string(view ? "," : "") + "{\"buffer\":0,\"byteOffset\":" + std::to_string(offset) +
              ",\"byteLength\":" + std::to_string(size) + (target ? ",\"target\":" + std::to_string(target) : "") + "}";
    accessors_ += std::string(view ? "," : "") + "{\"bufferView\":" + std::to_string(view) +
                  ",\"componentType\":" + std::to_string(component) + ",\"count\":" + std::to_string(count) +
                  ",\"type\":\"" + type + "\"" + extra + "}";
    return view;
  }
  std::string bytes_, views_, accessors_;
  int num_ = 0;
};

// glTF's base colour is linear; "#rrggbb" is sRGB.
std::string LinearColour(const std::string& hex, double opacity) {
  std::string out = "[";
  for (int k = 0; k < 3; ++k) {
    const double c = std::stoi(hex.substr(1 + 2 * k, 2), nullptr, 16) / 255.0;
    out += Number(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4)) + ",";
  }
  return out + Number(opacity) + "]";
}

void Append(std::vector<float>* out, const Vec3& v) { out->insert(out->end(), {float(v.x()), float(v.y()), float(v.z())}); }

// Quaternions of a channel keep the sign of the one before, so that no
// interpolation goes the long way round.
void Append(std::vector<float>* out, Eigen::Quaterniond q) {
  const std::size_t n = out->size();
  if (n >= 4 && (*out)[n - 4] * q.x() + (*out)[n - 3] * q.y() + (*out)[n - 2] * q.z() + (*out)[n - 1] * q.w() < 0)
    q.coeffs() = -q.coeffs();
  out->insert(out->end(), {float(q.x()), float(q.y()), float(q.z()), float(q.w())});
}

// The recorded frames the animation keeps, and their times from the first
// one in float32, strictly increasing: of frames whose times round to one
// float the last is kept (the run's last row stays last).
struct Keyframes {
  std::vector<int> frames;
  std::vector<float> times;
};
Keyframes KeyframesOf(const std::vector<double>& recorded) {
  Keyframes k;
  for (std::size_t f = 0; f < recorded.size(); ++f) {
    const float t = static_cast<float>(recorded[f] - recorded.front());
    if (!k.times.empty() && t <= k.times.back()) {
      k.frames.back() = static_cast<int>(f);
    } else {
      k.frames.push_back(static_cast<int>(f));
      k.times.push_back(t);
    }
  }
  return k;
}

std::string At(double t) { return " at t = " + Number(t) + " s"; }

}  // namespace

Gltf GltfBinary(const Scene& scene, const AnimationRecorder& recording, const std::string& title) {
  Buffer buffer;
  std::ostringstream meshes, materials, nodes, channels, samplers;
  const int num_bodies = static_cast<int>(scene.bodies.size());
  std::vector<std::string> primitives(num_bodies + 1);  // per holder: ground first
  std::vector<std::string> spring_nodes;
  int num_materials = 0, num_meshes = 0;
  for (std::size_t i = 0; i < scene.shapes.size(); ++i) {
    const Shape& s = scene.shapes[i];
    const Mesh mesh = Tessellate(s);
    const bool line = mesh.primitive == Mesh::Primitive::kLineStrip;
    materials << (num_materials ? "," : "") << "{\"name\":" << Quoted(s.name)
              << ",\"pbrMetallicRoughness\":{\"baseColorFactor\":" << LinearColour(s.color, s.opacity)
              << ",\"metallicFactor\":0.1,\"roughnessFactor\":0.6}" << (s.opacity < 1 ? ",\"alphaMode\":\"BLEND\"" : "")
              << (mesh.double_sided ? ",\"doubleSided\":true" : "") << "}";
    const Where vertex = [&](std::size_t) { return s.origin + ": shape '" + s.name + "': a vertex"; };
    std::string primitive = "{\"attributes\":{\"POSITION\":" +
                            std::to_string(buffer.Floats(mesh.positions, 3, "VEC3", kArrayBuffer, true, vertex));
    if (!line)
      primitive += ",\"NORMAL\":" +
                   std::to_string(buffer.Floats(VertexNormals(mesh), 3, "VEC3", kArrayBuffer, false, vertex));
    primitive += "}";
    if (!line) primitive += ",\"indices\":" + std::to_string(buffer.Indices(mesh.indices));
    primitive += ",\"material\":" + std::to_string(num_materials++) + ",\"mode\":" + (line ? "3" : "4") + "}";
    if (s.kind == "spring") {
      meshes << (num_meshes ? "," : "") << "{\"name\":" << Quoted(s.name) << ",\"primitives\":[" << primitive << "]}";
      spring_nodes.push_back("{\"name\":" + Quoted(s.name) + ",\"mesh\":" + std::to_string(num_meshes++) + "}");
    } else {
      std::string& list = primitives[s.body + 1];
      list += (list.empty() ? "" : ",") + primitive;
    }
  }
  std::vector<int> mesh_of(num_bodies + 1, -1);
  for (int h = 0; h <= num_bodies; ++h)
    if (!primitives[h].empty()) {
      meshes << (num_meshes ? "," : "") << "{\"primitives\":[" << primitives[h] << "]}";
      mesh_of[h] = num_meshes++;
    }
  const auto holder_node = [&](int h, const std::string& name) {
    return "{\"name\":" + Quoted(name) + (mesh_of[h] >= 0 ? ",\"mesh\":" + std::to_string(mesh_of[h]) : "") + "}";
  };
  // nodes: 0 the root, then the ground (when it has shapes), the bodies, the springs
  const bool ground = mesh_of[0] >= 0;
  const int first_body = ground ? 2 : 1, first_spring = first_body + num_bodies;
  nodes << "{\"name\":" << Quoted(title + " (z up)") << ",\"rotation\":[-0.7071067811865476,0,0,0.7071067811865476]"
        << ",\"children\":[";
  for (int k = 1; k < first_spring + static_cast<int>(spring_nodes.size()); ++k) nodes << (k > 1 ? "," : "") << k;
  nodes << "]}";
  if (ground) nodes << "," << holder_node(0, "Base0");
  for (int b = 0; b < num_bodies; ++b) nodes << "," << holder_node(b + 1, scene.bodies[b].label);
  for (const std::string& node : spring_nodes) nodes << "," << node;

  // the motion, at the keyframes; `what` names a channel's owner
  const Keyframes keys = KeyframesOf(recording.times());
  const auto time_of = [&](std::size_t key) { return recording.times()[keys.frames[key]]; };
  int input = -1, num_samplers = 0;
  const auto channel = [&](int node, const char* path, const std::vector<float>& values, const char* type,
                           const std::string& what) {
    if (keys.frames.empty()) return;  // no row recorded: the scene without motion (an accessor holds one at least)
    if (input < 0)
      input = buffer.Floats(keys.times, 1, "SCALAR", 0, true,
                            [&](std::size_t key) { return "the time from the start" + At(time_of(key)); });
    const int output = buffer.Floats(values, type[3] == '4' ? 4 : 3, type, 0, false,
                                     [&](std::size_t key) { return what + At(time_of(key)) + ": its " + path; });
    samplers << (num_samplers ? "," : "") << "{\"input\":" << input << ",\"output\":" << output
             << ",\"interpolation\":\"LINEAR\"}";
    channels << (num_samplers ? "," : "") << "{\"sampler\":" << num_samplers << ",\"target\":{\"node\":" << node
             << ",\"path\":\"" << path << "\"}}";
    ++num_samplers;
  };
  for (int b = 0; b < num_bodies; ++b) {
    std::vector<float> translation, rotation;
    for (const int f : keys.frames) {
      const mech::Pose pose = recording.Pose(f, b);
      Append(&translation, pose.p);
      Append(&rotation, Eigen::Quaterniond(pose.R));
    }
    const std::string what = "body '" + scene.bodies[b].label + "'";
    channel(first_body + b, "translation", translation, "VEC3", what);
    channel(first_body + b, "rotation", rotation, "VEC4", what);
  }
  int spring = 0;
  for (const Shape& s : scene.shapes) {
    if (s.kind != "spring") continue;
    std::vector<float> translation, rotation, scale;
    for (const int f : keys.frames) {
      const SpringTransform placed = PlaceSpring(s, recording.Pose(f, s.body), recording.Pose(f, s.body2));
      Append(&translation, placed.translation);
      Append(&rotation, placed.rotation);
      Append(&scale, Vec3(1, placed.length, 1));
    }
    const int node = first_spring + spring++;
    const std::string what = s.origin + ": spring '" + s.name + "'";
    channel(node, "translation", translation, "VEC3", what);
    channel(node, "rotation", rotation, "VEC4", what);
    channel(node, "scale", scale, "VEC3", what);
  }

  std::ostringstream json;
  json << "{\"asset\":{\"version\":\"2.0\",\"generator\":\"mechflow\"},\"scene\":0,\"scenes\":[{\"name\":" << Quoted(title)
       << ",\"nodes\":[0]}],\"nodes\":[" << nodes.str() << "],\"meshes\":[" << meshes.str() << "],\"materials\":["
       << materials.str() << "]";
  if (num_samplers)
    json << ",\"animations\":[{\"name\":\"motion\",\"channels\":[" << channels.str() << "],\"samplers\":["
         << samplers.str() << "]}]";
  json << ",\"buffers\":[{\"byteLength\":" << buffer.bytes().size() << "}],\"bufferViews\":" << buffer.ViewsJson()
       << ",\"accessors\":" << buffer.AccessorsJson() << "}";

  // GLB: a 12-byte header, the JSON chunk (padded with blanks), the binary chunk
  std::string text = json.str();
  while (text.size() % 4) text += ' ';
  const std::string& bin = buffer.bytes();
  std::string glb;
  const auto word = [&](std::uint32_t v) { glb.append(reinterpret_cast<const char*>(&v), 4); };  // little-endian hosts
  word(0x46546C67);  // "glTF"
  word(2);
  word(static_cast<std::uint32_t>(12 + 8 + text.size() + 8 + bin.size()));
  word(static_cast<std::uint32_t>(text.size()));
  word(0x4E4F534A);  // "JSON"
  glb += text;
  word(static_cast<std::uint32_t>(bin.size()));
  word(0x004E4942);  // "BIN"
  glb += bin;
  const int num_keys = static_cast<int>(keys.frames.size());
  return {std::move(glb), num_keys, static_cast<int>(recording.times().size()) - num_keys};
}

}  // namespace mechflow::graphics
