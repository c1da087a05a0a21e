#include "graphics/scene.h"

#include <cmath>
#include <sstream>

#include "blocks/csv.h"
#include "blocks/library/mechanism_block.h"
#include "blocks/suggest.h"
#include "diagrams/evaluator.h"
#include "mech/errors.h"

namespace mechflow::graphics {
namespace {

const std::vector<std::string> kKinds = {"box", "sphere", "cylinder", "polyline", "spring"};

// Reads one <shape>'s attributes with messages "file:line: shape 'name': ...".
class ShapeReader {
 public:
  ShapeReader(const diagrams::ElementDesc& e, const diagrams::Evaluator& eval, std::string what)
      : e_(e), eval_(eval), what_(std::move(what)) {}

  bool Has(const std::string& attribute) const { return e_.Find(attribute) != nullptr; }
  std::string What(const std::string& attribute) const {
    const diagrams::Attribute* a = e_.Find(attribute);
    return (a ? a->loc.str() : e_.loc.str()) + ": " + what_ + " '" + attribute + "'";
  }
  double Number(const std::string& attribute, double fallback) const {
    return Has(attribute) ? eval_.Number(e_.Text(attribute), What(attribute)) : fallback;
  }
  double Positive(const std::string& attribute, double fallback) const {
    const double v = Number(attribute, fallback);
    if (!(v > 0.0) || !std::isfinite(v)) throw InputError(What(attribute) + ": must be > 0, got " + blocks::CsvNumber(v));
    return v;
  }
  Vec3 Vector(const std::string& attribute, const Vec3& fallback) const {
    if (!Has(attribute)) return fallback;
    const std::vector<double> v = eval_.Numbers(e_.Text(attribute), What(attribute));
    if (v.size() != 3) throw InputError(What(attribute) + ": expected three numbers \"x y z\"");
    return {v[0], v[1], v[2]};
  }
  std::vector<Vec3> Points(const std::string& attribute) const {
    std::vector<Vec3> points;
    for (const auto& row : eval_.Table(e_.Text(attribute), What(attribute))) {
      if (row.size() != 3) throw InputError(What(attribute) + ": each point is three numbers \"x y z\"");
      points.emplace_back(row[0], row[1], row[2]);
    }
    return points;
  }

 private:
  const diagrams::ElementDesc& e_;
  const diagrams::Evaluator& eval_;
  std::string what_;
};

// Cardan 1-2-3 angles [rad]: about x, then the new y, then the new z.
Mat3 Cardan(const Vec3& a) {
  return mech::AxisRotation(Vec3::UnitX(), a.x()) * mech::AxisRotation(Vec3::UnitY(), a.y()) *
         mech::AxisRotation(Vec3::UnitZ(), a.z());
}

bool IsColour(const std::string& c) {
  if (c.size() != 7 || c[0] != '#') return false;
  for (std::size_t i = 1; i < c.size(); ++i)
    if (!std::isxdigit(static_cast<unsigned char>(c[i]))) return false;
  return true;
}

// JSON string literal.
std::string Quoted(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (static_cast<unsigned char>(c) < 0x20) {
      char buffer[8];
      std::snprintf(buffer, sizeof buffer, "\\u%04x", c);
      out += buffer;
      continue;
    }
    out += c;
  }
  return out + "\"";
}

std::string Json(const Vec3& v) {
  return "[" + blocks::CsvNumber(v.x()) + "," + blocks::CsvNumber(v.y()) + "," + blocks::CsvNumber(v.z()) + "]";
}

}  // namespace

Scene BuildScene(const diagrams::LoadedDiagram& loaded) {
  Scene scene;
  const diagrams::Evaluator eval(loaded.lua.get(), loaded.identifiers.get());
  for (const diagrams::ElementDesc& m : loaded.description.mechanisms) {
    const std::string mechanism = m.Text("name");
    const blocks::MechanismBlock* block = nullptr;
    int block_index = -1;
    for (int b = 0; b < loaded.diagram->num_blocks(); ++b)
      if (loaded.diagram->block(b).name() == mechanism)
        if ((block = dynamic_cast<const blocks::MechanismBlock*>(&loaded.diagram->block(b)))) {
          block_index = b;
          break;
        }
    if (!block) continue;
    const mech::Model& model = block->mechanism().model();
    int count = 0;
    for (const diagrams::ElementDesc& e : m.children) {
      if (e.tag != "shape") continue;
      ++count;
      Shape s;
      s.kind = e.Text("type");
      s.name = e.Text("name", s.kind + " " + std::to_string(count));
      s.origin = e.loc.str();
      const ShapeReader r(e, eval, "shape '" + s.name + "'");
      if (std::find(kKinds.begin(), kKinds.end(), s.kind) == kKinds.end())
        throw InputError(r.What("type") + ": unknown shape type '" + s.kind + "'" + blocks::DidYouMean(s.kind, kKinds) +
                         "; expected one of " + blocks::JoinNames(kKinds));
      // the body a name means: -1 for Base0, else its index in scene.bodies
      const auto body_of = [&](const std::string& attribute) {
        const std::string name = e.Text(attribute, "Base0");
        if (name == "Base0") return -1;
        const int body = model.FindBody(name);
        if (body < 0) {
          std::vector<std::string> names;
          for (const mech::Body& b : model.bodies()) names.push_back(b.name);
          throw InputError(r.What(attribute) + ": mechanism '" + mechanism + "' has no body '" + name + "'" +
                           blocks::DidYouMean(name, names));
        }
        const std::string label = mechanism + "." + name;
        for (std::size_t i = 0; i < scene.bodies.size(); ++i)
          if (scene.bodies[i].label == label) return static_cast<int>(i);
        scene.bodies.push_back({label, block_index, body});
        return static_cast<int>(scene.bodies.size()) - 1;
      };
      s.body = body_of("body");
      s.position = r.Vector("position", Vec3::Zero());
      s.rotation = Cardan(r.Vector("rotation", Vec3::Zero()));
      if (s.kind == "box") {
        s.size = r.Vector("size", Vec3::Ones());
        if (!(s.size.minCoeff() > 0.0)) throw InputError(r.What("size") + ": every edge must be > 0");
      } else if (s.kind == "sphere") {
        s.radius = r.Positive("radius", 0.1);
      } else if (s.kind == "cylinder") {
        s.radius = r.Positive("radius", 0.05);
        s.length = r.Positive("length", 0.2);
        const Vec3 axis = r.Vector("axis", Vec3::UnitZ());
        if (!(axis.norm() > 0.0)) throw InputError(r.What("axis") + ": the axis is zero");
        s.axis = axis.normalized();
      } else if (s.kind == "polyline") {
        if (!r.Has("points")) throw InputError(e.loc.str() + ": shape '" + s.name + "': a polyline needs 'points'");
        s.points = r.Points("points");
        if (s.points.size() < 2) throw InputError(r.What("points") + ": a polyline needs at least two points");
      } else if (s.kind == "spring") {
        s.body2 = body_of("body2");
        s.point1 = r.Vector("point1", Vec3::Zero());
        s.point2 = r.Vector("point2", Vec3::Zero());
        s.radius = r.Positive("radius", 0.03);
        const double coils = r.Number("coils", 8);
        if (!(coils >= 1 && coils <= 1000 && coils == std::floor(coils)))
          throw InputError(r.What("coils") + ": a whole number from 1 to 1000, got " + blocks::CsvNumber(coils));
        s.coils = static_cast<int>(coils);
      }
      s.color = e.Text("color", s.color);
      if (!IsColour(s.color)) throw InputError(r.What("color") + ": expected \"#rrggbb\", got '" + s.color + "'");
      s.opacity = r.Number("opacity", 1.0);
      if (!(s.opacity >= 0.0 && s.opacity <= 1.0))
        throw InputError(r.What("opacity") + ": must lie in [0, 1], got " + blocks::CsvNumber(s.opacity));
      scene.shapes.push_back(std::move(s));
    }
  }
  return scene;
}

std::string SceneJson(const Scene& scene, const std::string& title) {
  std::ostringstream o;
  o << "{\"title\":" << Quoted(title) << ",\"bodies\":[";
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) o << (i ? "," : "") << Quoted(scene.bodies[i].label);
  o << "],\"shapes\":[";
  for (std::size_t i = 0; i < scene.shapes.size(); ++i) {
    const Shape& s = scene.shapes[i];
    o << (i ? "," : "") << "{\"kind\":" << Quoted(s.kind) << ",\"name\":" << Quoted(s.name) << ",\"body\":" << s.body
      << ",\"position\":" << Json(s.position) << ",\"rotation\":[";
    for (int k = 0; k < 9; ++k) o << (k ? "," : "") << blocks::CsvNumber(s.rotation(k / 3, k % 3));  // row-major
    o << "],\"color\":" << Quoted(s.color) << ",\"opacity\":" << blocks::CsvNumber(s.opacity);
    if (s.kind == "box") o << ",\"size\":" << Json(s.size);
    if (s.kind == "sphere" || s.kind == "cylinder" || s.kind == "spring")
      o << ",\"radius\":" << blocks::CsvNumber(s.radius);
    if (s.kind == "cylinder") o << ",\"length\":" << blocks::CsvNumber(s.length) << ",\"axis\":" << Json(s.axis);
    if (s.kind == "polyline") {
      o << ",\"points\":[";
      for (std::size_t k = 0; k < s.points.size(); ++k) o << (k ? "," : "") << Json(s.points[k]);
      o << "]";
    }
    if (s.kind == "spring")
      o << ",\"body2\":" << s.body2 << ",\"point1\":" << Json(s.point1) << ",\"point2\":" << Json(s.point2)
        << ",\"coils\":" << s.coils;
    o << "}";
  }
  o << "]}";
  return o.str();
}

}  // namespace mechflow::graphics
