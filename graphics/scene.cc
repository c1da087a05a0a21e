#include "graphics/scene.h"

#include <algorithm>
#include <cmath>

#include "blocks/library/mechanism_block.h"
#include "blocks/outputs/csv.h"
#include "blocks/support/suggest.h"
#include "diagrams/element_table.h"
#include "diagrams/evaluator.h"
#include "mech/errors.h"
#include "scripting/compiled_expression.h"

namespace mechflow::graphics {
namespace {

// Reads one <shape>'s attributes, with messages "file:line: shape 'name'
// 'attribute': ...", noting the identifiers every number names.
class ShapeReader {
 public:
  ShapeReader(const diagrams::ElementDesc& e, const diagrams::LoadedDiagram& loaded, std::string what, Shape* shape)
      : e_(e), loaded_(loaded), what_(std::move(what)), shape_(shape) {}

  bool Has(const std::string& attribute) const { return e_.Find(attribute) != nullptr; }
  std::string What(const std::string& attribute) const {
    const diagrams::Attribute* a = e_.Find(attribute);
    return (a ? a->loc.str() : e_.loc.str()) + ": " + what_ + " '" + attribute + "'";
  }
  std::vector<double> Numbers(const std::string& attribute) const {
    std::vector<double> out;
    for (const std::string& item : diagrams::Split(e_.Text(attribute), " \t\r\n,")) out.push_back(Value(attribute, item));
    if (out.empty()) throw InputError(What(attribute) + ": expected at least one number");
    return out;
  }
  double Number(const std::string& attribute, double fallback) const {
    if (!Has(attribute)) return fallback;
    const std::vector<double> v = Numbers(attribute);
    if (v.size() != 1) throw InputError(What(attribute) + ": expected one number");
    return v[0];
  }
  double Positive(const std::string& attribute, double fallback) const {
    const double v = Number(attribute, fallback);
    if (!(v > 0.0) || !std::isfinite(v)) throw InputError(What(attribute) + ": must be > 0, got " + blocks::CsvNumber(v));
    return v;
  }
  int Whole(const std::string& attribute, int fallback, int least, int most) const {
    const double v = Number(attribute, fallback);
    if (!(v >= least && v <= most && v == std::floor(v)))
      throw InputError(What(attribute) + ": a whole number from " + std::to_string(least) + " to " +
                       std::to_string(most) + ", got " + blocks::CsvNumber(v));
    return static_cast<int>(v);
  }
  Vec3 Vector(const std::string& attribute, const Vec3& fallback) const {
    if (!Has(attribute)) return fallback;
    const std::vector<double> v = Numbers(attribute);
    if (v.size() != 3) throw InputError(What(attribute) + ": expected three numbers \"x y z\"");
    return {v[0], v[1], v[2]};
  }
  Vec3 PositiveVector(const std::string& attribute, const Vec3& fallback) const {
    const Vec3 v = Vector(attribute, fallback);
    if (!(v.minCoeff() > 0.0)) throw InputError(What(attribute) + ": every one must be > 0");
    return v;
  }
  Vec3 Axis(const Vec3& fallback) const {
    const Vec3 axis = Vector("axis", fallback);
    if (!(axis.norm() > 0.0)) throw InputError(What("axis") + ": the axis is zero");
    return axis.normalized();
  }
  std::vector<Vec3> Points(const std::string& attribute) const {
    std::vector<Vec3> points;
    for (const std::string& row : diagrams::Split(e_.Text(attribute), ";")) {
      std::vector<double> p;
      for (const std::string& item : diagrams::Split(row, " \t\r\n,")) p.push_back(Value(attribute, item));
      if (p.size() != 3) throw InputError(What(attribute) + ": each point is three numbers \"x y z\"");
      points.emplace_back(p[0], p[1], p[2]);
    }
    return points;
  }
  // An interval "from to" of a curve's or surface's parameter.
  std::pair<double, double> Range(const std::string& attribute) const {
    if (!Has(attribute)) throw InputError(e_.loc.str() + ": " + what_ + ": needs the range '" + attribute + "' (\"from to\")");
    const std::vector<double> r = Numbers(attribute);
    if (r.size() != 2 || !(r[0] < r[1])) throw InputError(What(attribute) + ": expected \"from to\" with from < to");
    return {r[0], r[1]};
  }
  // x(u) or x(u, v) at `u` and `v`, from the attributes x, y, z.
  void Sample(const std::vector<std::string>& parameters, int samples_u, int samples_v, Parametric* out) const {
    auto& lua = *loaded_.lua;
    std::vector<std::unique_ptr<scripting::CompiledExpression>> xyz;
    for (const char* c : {"x", "y", "z"}) {
      if (!Has(c)) throw InputError(e_.loc.str() + ": " + what_ + ": needs '" + c + "', an expression of " +
                                    (parameters.size() == 1 ? "u" : "u and v"));
      xyz.push_back(std::make_unique<scripting::CompiledExpression>(lua, e_.Text(c), parameters, *loaded_.identifiers,
                                                                    "=" + What(c)));
      for (const std::string& name : xyz.back()->identifiers_used()) Note(loaded_.identifiers->Find(name));
    }
    const auto [u0, u1] = Range("u");
    const auto [v0, v1] = parameters.size() == 2 ? Range("v") : std::pair<double, double>{0, 0};
    out->samples_u = samples_u, out->samples_v = samples_v;
    out->points.clear();
    for (int j = 0; j <= samples_v; ++j)
      for (int i = 0; i <= samples_u; ++i) {
        const double args[2] = {u0 + (u1 - u0) * i / samples_u, samples_v ? v0 + (v1 - v0) * j / samples_v : 0.0};
        Vec3 p;
        for (int k = 0; k < 3; ++k) {
          try {
            p[k] = xyz[k]->Evaluate(args);
          } catch (const SimulationError& e) {
            // evaluated when the diagram is loaded: a value it cannot give is bad input, not a failed run
            throw InputError(e.what());
          }
        }
        out->points.push_back(p);
      }
  }

 private:
  double Value(const std::string& attribute, const std::string& text) const {
    double value = 0.0;
    if (scripting::ParseNumber(text, &value)) return value;
    for (const int id : loaded_.identifiers->NamedIn(text)) Note(id);
    return loaded_.identifiers->EvaluateFollowing(*loaded_.lua, text, What(attribute));
  }
  void Note(int id) const {
    if (id >= 0 && std::find(shape_->identifiers.begin(), shape_->identifiers.end(), id) == shape_->identifiers.end())
      shape_->identifiers.push_back(id);
  }

  const diagrams::ElementDesc& e_;
  const diagrams::LoadedDiagram& loaded_;
  std::string what_;
  Shape* shape_;
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

}  // namespace

const std::vector<std::string>& ShapeKinds() {
  static const std::vector<std::string> kinds = diagrams::FindElementSpec("shape")->VariantNames();
  return kinds;
}

Shape ShapeBuilder::Read(const diagrams::ElementDesc& m, const diagrams::ElementDesc& e, int number,
                         std::vector<SceneBody>* bodies) const {
  const std::string mechanism = m.Text("name");
  const blocks::MechanismBlock* block = nullptr;
  int block_index = -1;
  for (int b = 0; b < loaded_.diagram->num_blocks() && !block; ++b)
    if (loaded_.diagram->block(b).name() == mechanism)
      if ((block = dynamic_cast<const blocks::MechanismBlock*>(&loaded_.diagram->block(b)))) block_index = b;
  if (!block) throw InputError(e.loc.str() + ": mechanism '" + mechanism + "' was not built");
  const mech::Model& model = block->mechanism().model();

  Shape s;
  s.kind = e.Text("type");
  s.name = e.Text("name", s.kind + " " + std::to_string(number));
  s.origin = e.loc.str();
  const ShapeReader r(e, loaded_, "shape '" + s.name + "'", &s);
  const auto& kinds = ShapeKinds();
  if (std::find(kinds.begin(), kinds.end(), s.kind) == kinds.end())
    throw InputError(r.What("type") + ": unknown shape type '" + s.kind + "'" + blocks::DidYouMean(s.kind, kinds) +
                     "; expected one of " + blocks::JoinNames(kinds));
  // an attribute this kind does not use would change nothing: refused, by the
  // format's element table (the reader checks it too; a description built in
  // code reaches here unchecked)
  diagrams::CheckAttributes("shape", e.attributes, e.loc);
  // the body a name means: -1 for Base0, else its index in `bodies`
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
    for (std::size_t i = 0; i < bodies->size(); ++i)
      if ((*bodies)[i].label == label) return static_cast<int>(i);
    bodies->push_back({label, block_index, body});
    return static_cast<int>(bodies->size()) - 1;
  };
  s.body = body_of("body");
  s.position = r.Vector("position", Vec3::Zero());
  s.rotation = Cardan(r.Vector("rotation", Vec3::Zero()));
  const std::string& k = s.kind;
  if (k == "box") {
    s.size = r.PositiveVector("size", Vec3::Ones());
  } else if (k == "sphere" || k == "circle") {
    s.radius = r.Positive("radius", 0.1);
  } else if (k == "ellipsoid") {
    s.size = r.PositiveVector("size", Vec3::Constant(0.1));  // the three radii
  } else if (k == "cylinder" || k == "cone") {
    s.radius = r.Positive("radius", 0.05);
    s.length = r.Positive("length", 0.2);
    s.axis = r.Axis(Vec3::UnitZ());
    if (k == "cone") {
      s.radius2 = r.Number("radius2", 0.0);
      if (!(s.radius2 >= 0.0)) throw InputError(r.What("radius2") + ": must be >= 0");
    }
  } else if (k == "plane") {
    const std::vector<double> size = r.Has("size") ? r.Numbers("size") : std::vector<double>{1, 1};
    if (size.size() != 2 || !(size[0] > 0 && size[1] > 0))
      throw InputError(r.What("size") + ": expected two edges > 0 \"a b\" (along the shape's x and y)");
    s.size = {size[0], size[1], 0};
  } else if (k == "gear") {
    s.radius = r.Positive("radius", 0.1);
    s.length = r.Positive("width", 0.05);
    s.tooth_height = r.Positive("tooth_height", 0.2 * s.radius);
    if (!(s.tooth_height < 2 * s.radius))
      throw InputError(r.What("tooth_height") + ": must be below twice the radius (the teeth's roots at r - h/2)");
    s.teeth = r.Whole("teeth", 20, 3, 1000);
    s.taper = r.Positive("taper", 1.0);
    s.axis = r.Axis(Vec3::UnitX());
  } else if (k == "polyline") {
    if (!r.Has("points")) throw InputError(e.loc.str() + ": shape '" + s.name + "': a polyline needs 'points'");
    s.points = r.Points("points");
    if (s.points.size() < 2) throw InputError(r.What("points") + ": a polyline needs at least two points");
  } else if (k == "curve") {
    r.Sample({"u"}, r.Whole("samples", 100, 1, 100000), 0, &s.parametric);
  } else if (k == "surface") {
    const std::vector<double> n = r.Has("samples") ? r.Numbers("samples") : std::vector<double>{32, 16};
    if (n.size() != 2 || n[0] < 1 || n[1] < 1 || n[0] * n[1] > 250000 || n[0] != std::floor(n[0]) ||
        n[1] != std::floor(n[1]))
      throw InputError(r.What("samples") + ": expected two whole numbers \"nu nv\" >= 1 with nu nv <= 250000");
    r.Sample({"u", "v"}, static_cast<int>(n[0]), static_cast<int>(n[1]), &s.parametric);
  } else if (k == "spring") {
    s.body2 = body_of("body2");
    s.point1 = r.Vector("point1", Vec3::Zero());
    s.point2 = r.Vector("point2", Vec3::Zero());
    s.radius = r.Positive("radius", 0.03);
    s.coils = r.Whole("coils", 8, 1, 1000);
  }
  s.color = e.Text("color", s.color);
  if (!IsColour(s.color)) throw InputError(r.What("color") + ": expected \"#rrggbb\", got '" + s.color + "'");
  s.opacity = r.Number("opacity", 1.0);
  if (!(s.opacity >= 0.0 && s.opacity <= 1.0))
    throw InputError(r.What("opacity") + ": must lie in [0, 1], got " + blocks::CsvNumber(s.opacity));
  return s;
}

Scene BuildScene(const diagrams::LoadedDiagram& loaded) {
  Scene scene;
  const ShapeBuilder builder(loaded);
  for (const diagrams::ElementDesc& m : loaded.description.mechanisms) {
    int number = 0;
    for (const diagrams::ElementDesc& e : m.children) {
      if (e.tag != "shape") continue;
      scene.shapes.push_back(builder.Read(m, e, ++number, &scene.bodies));
      scene.sources.push_back({&m, &e, number});
    }
  }
  return scene;
}

}  // namespace mechflow::graphics
