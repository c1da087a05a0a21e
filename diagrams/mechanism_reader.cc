#include "diagrams/mechanism_reader.h"

namespace mechflow::diagrams {

void RequireAtLeast(const MechanismReader& r, const ElementDesc& e, const std::string& attribute,
                    const mech::Parameter& p, double minimum, const std::string& what) {
  if (!p.is_constant() || p.value >= minimum) return;
  char found[32];
  std::snprintf(found, sizeof found, "%g", p.value);
  throw InputError(r.What(e, attribute) + ": " + what + " (found " + found + ")");
}

mech::Pose Frame(const MechanismReader& r, const ElementDesc& e, const std::string& point,
                 const std::string& rotation, const mech::BodySpec* body) {
  mech::Pose pose = mech::Pose::Translation(r.Point(e, point, body));
  if (r.Has(e, rotation)) {
    const Vec3 a = r.Vector(e, rotation, Vec3::Zero());  // Cardan 1-2-3 [rad]
    pose.R = mech::AxisRotation(Vec3::UnitX(), a.x()) * mech::AxisRotation(Vec3::UnitY(), a.y()) *
             mech::AxisRotation(Vec3::UnitZ(), a.z());
  }
  return pose;
}

int BodyIndex(const mech::Model& model, const ElementDesc& e, const std::string& attribute) {
  const std::string name = e.Text(attribute);
  const int index = model.FindBody(name);
  if (index >= 0) return index;
  std::vector<std::string> names;
  for (const auto& b : model.bodies()) names.push_back(b.name);
  const Attribute* a = e.Find(attribute);
  throw InputError((a ? a->loc : e.loc).str() + ": " + e.tag + " '" + e.Text("name") + "': unknown body '" + name +
                   "'" + blocks::DidYouMean(name, names) + "; bodies: " + blocks::JoinNames(names));
}

Vec3 BodyPoint(const MechanismReader& r, const mech::Model& model, const ElementDesc& e, const std::string& attribute,
               int body) {
  if (!r.Has(e, attribute)) return Vec3::Zero();
  const std::string text = Trim(e.Text(attribute));
  for (const auto& p : model.bodies()[body].points)
    if (p.name == text) return p.position;
  return r.Vector(e, attribute, Vec3::Zero());
}

int DofIndex(const mech::Model& model, const ElementDesc& e, const std::string& attribute) {
  const std::string name = e.Text(attribute);
  const int index = model.FindDof(name);
  if (index >= 0) return index;
  std::vector<std::string> names;
  for (const auto& d : model.dofs()) names.push_back(d.name);
  const Attribute* a = e.Find(attribute);
  throw InputError((a ? a->loc : e.loc).str() + ": " + e.tag + " '" + e.Text("name") + "': unknown coordinate '" +
                   name + "'" + blocks::DidYouMean(name, names) + "; coordinates: " + blocks::JoinNames(names));
}

// The frictional element's parameters, on a line between points or on a

}  // namespace mechflow::diagrams
