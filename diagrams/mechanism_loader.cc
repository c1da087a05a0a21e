#include "diagrams/mechanism_loader.h"

#include <algorithm>
#include <cctype>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include "blocks/library/mechanism_block.h"
#include "blocks/support/suggest.h"
#include "diagrams/attribute_units.h"
#include "mech/applied_force.h"
#include "mech/bipolar_force.h"
#include "mech/bushing.h"
#include "mech/circle_plane_contact.h"
#include "mech/elastic_friction2_force.h"
#include "mech/elastic_friction_force.h"
#include "mech/frictional_force.h"
#include "mech/gearing.h"
#include "mech/joint_force.h"
#include "mech/model_builder.h"
#include "mech/points_plane_contact.h"
#include "scripting/lua_scalar_function.h"
#include "scripting/jet_expression.h"

namespace mechflow::diagrams {
namespace {

using mech::Vec3;

// Reads one <mechanism>: the identifiers it may use, its inputs, and helpers
// that turn attribute text into numbers, vectors and parameters.
class MechanismReader {
 public:
  MechanismReader(const ElementDesc& m, const Evaluator& eval) : eval_(eval) {
    for (const ElementDesc& e : m.children) {
      if (e.tag != "input") continue;
      const std::string name = e.Text("name");
      if (!eval.identifiers()->Has(name))
        throw InputError(e.loc.str() + ": input '" + name + "' must name an identifier of the diagram" +
                         blocks::DidYouMean(name, eval.identifiers()->Names()) +
                         " (its value there is the value before the first evaluation)");
      inputs_.push_back(scripting::ToLower(name));
    }
    // Expressions that follow inputs take them as arguments; Lua arguments may
    // not share a name with an identifier, so those expressions see the
    // identifiers without the inputs.
    const scripting::IdentifierTable& ids = *eval.identifiers();
    for (int i = 0; i < ids.size(); ++i) {
      if (std::find(inputs_.begin(), inputs_.end(), ids.name(i)) != inputs_.end()) continue;
      char value[32];
      std::snprintf(value, sizeof value, "%.17g", ids.value(i));
      non_inputs_.Add(ids.name(i), value, ids.origin(i));
    }
    non_inputs_.Evaluate(*eval.lua());
  }

  const std::vector<std::string>& inputs() const { return inputs_; }
  const Evaluator& eval() const { return eval_; }

  std::string What(const ElementDesc& e, const std::string& attribute) const {
    const Attribute* a = e.Find(attribute);
    return (a ? a->loc.str() : e.loc.str()) + ": " + e.tag + " '" + e.Text("name") + "' attribute '" + attribute + "'";
  }
  [[noreturn]] void Fail(const ElementDesc& e, const std::string& message) const {
    throw InputError(e.loc.str() + ": " + e.tag + " '" + e.Text("name") + "': " + message);
  }
  bool Has(const ElementDesc& e, const std::string& attribute) const { return e.Find(attribute) != nullptr; }
  // The identifiers the attribute uses against its unit (attribute_units.h);
  // "force[1]" is an element of "force".
  void CheckUnit(const ElementDesc& e, const std::string& attribute, bool list) const {
    const std::string base = attribute.substr(0, attribute.find('['));
    eval_.CheckUnit(e.Text(attribute), list, base, AttributeUnit(e.tag, e.Text("type"), base), What(e, attribute));
  }

  double Number(const ElementDesc& e, const std::string& attribute, double fallback) const {
    if (!Has(e, attribute)) return fallback;
    RejectInputs(e, attribute);
    CheckUnit(e, attribute, false);
    return eval_.Number(e.Text(attribute), What(e, attribute));
  }
  std::vector<double> Numbers(const ElementDesc& e, const std::string& attribute, std::size_t count) const {
    RejectInputs(e, attribute);
    CheckUnit(e, attribute, true);
    std::vector<double> v = eval_.Numbers(e.Text(attribute), What(e, attribute));
    if (v.size() != count)
      throw InputError(What(e, attribute) + ": expected " + std::to_string(count) + " numbers, found " +
                       std::to_string(v.size()));
    return v;
  }
  Vec3 Vector(const ElementDesc& e, const std::string& attribute, const Vec3& fallback) const {
    if (!Has(e, attribute)) return fallback;
    const auto v = Numbers(e, attribute, 3);
    return {v[0], v[1], v[2]};
  }
  // A point on a body: "x y z", or the name of one of the body's <point>s.
  Vec3 Point(const ElementDesc& e, const std::string& attribute, const mech::BodySpec* body) const {
    if (!Has(e, attribute)) return Vec3::Zero();
    const std::string text = Trim(e.Text(attribute));
    if (body)
      for (const auto& p : body->points)
        if (p.name == text) return p.position;
    return Vector(e, attribute, Vec3::Zero());
  }

  // A parameter: a constant, or a function of [t, inputs...] when the text
  // mentions an input (or t).
  mech::Parameter Param(const ElementDesc& e, const std::string& attribute, double fallback) const {
    if (!Has(e, attribute)) return fallback;
    const std::string text = e.Text(attribute);
    CheckUnit(e, attribute, false);
    if (!MentionsInputOrTime(text)) return eval_.Number(text, What(e, attribute));
    mech::Parameter p;
    p.function = Function(text, {"t"}, What(e, attribute));
    p.uses_inputs = MentionsInput(text);
    return p;
  }

  // A Lua function of `leading` arguments then the inputs, named with the
  // spelling the text uses (Lua arguments are case-sensitive, identifiers not).
  std::shared_ptr<const mech::ScalarFunction> Function(const std::string& text, std::vector<std::string> leading,
                                                       const std::string& what) const {
    for (const std::string& input : inputs_) leading.push_back(SpellingIn(text, input));
    return std::make_shared<scripting::LuaScalarFunction>(*eval_.lua(), text, leading, non_inputs_, "=" + what);
  }

  static std::vector<std::string> Names(const std::string& text) {
    std::vector<std::string> names;
    for (std::size_t i = 0; i < text.size();) {
      if (std::isalpha(static_cast<unsigned char>(text[i])) || text[i] == '_') {
        std::size_t j = i;
        while (j < text.size() && (std::isalnum(static_cast<unsigned char>(text[j])) || text[j] == '_')) ++j;
        names.push_back(text.substr(i, j - i));
        i = j;
      } else {
        ++i;
      }
    }
    return names;
  }
  bool MentionsInput(const std::string& text) const {
    for (const std::string& n : Names(text))
      if (std::find(inputs_.begin(), inputs_.end(), scripting::ToLower(n)) != inputs_.end()) return true;
    return false;
  }
  bool MentionsInputOrTime(const std::string& text) const {
    for (const std::string& n : Names(text)) {
      if (n == "t") return true;
      if (std::find(inputs_.begin(), inputs_.end(), scripting::ToLower(n)) != inputs_.end()) return true;
    }
    return false;
  }
  static std::string SpellingIn(const std::string& text, const std::string& lower) {
    for (const std::string& n : Names(text))
      if (scripting::ToLower(n) == lower) return n;
    return lower;
  }

 private:
  void RejectInputs(const ElementDesc& e, const std::string& attribute) const {
    for (const std::string& n : Names(e.Text(attribute)))
      if (std::find(inputs_.begin(), inputs_.end(), scripting::ToLower(n)) != inputs_.end())
        throw InputError(What(e, attribute) + ": uses the input '" + n +
                         "', but this attribute is fixed when the mechanism is built (inputs may drive force "
                         "parameters and applied forces)");
  }

  const Evaluator& eval_;
  std::vector<std::string> inputs_;
  scripting::IdentifierTable non_inputs_;
};

// Bad input (issue 4, item 7): a stiffness, damping or friction that is a
// constant below `minimum` is an error at the attribute's file:line.
// Parameters that follow inputs are checked by their elements at run time.
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

mech::TransformSpec Dof(mech::TransformType type, const Vec3& axis, double q0, double v0, bool locked,
                        const std::string& name, const std::string& origin) {
  mech::TransformSpec et;
  et.type = type;
  et.axis = axis;
  et.value = q0;
  et.rate = v0;
  et.locked = locked;
  et.dof_name = name;
  et.origin = origin;
  return et;
}

const std::vector<std::string> kJointTypes = {"rotational", "translational", "fixed",      "cardan6",
                                              "quaternion", "generalized",   "convel"};
const std::vector<std::string> kEtTypes = {"tc", "tt", "tv", "rc", "rt", "rv"};

mech::JointSpec ReadJoint(const MechanismReader& r, const ElementDesc& e,
                          const std::map<std::string, mech::BodySpec>& bodies, const Evaluator& eval) {
  mech::JointSpec j;
  j.name = e.Text("name");
  j.body1 = e.Text("body1");
  j.body2 = e.Text("body2");
  j.origin = e.loc.str();
  auto body = [&](const std::string& name) -> const mech::BodySpec* {
    const auto it = bodies.find(name);
    return it == bodies.end() ? nullptr : &it->second;
  };
  j.frame1 = Frame(r, e, "point1", "rotation1", body(j.body1));
  j.frame2 = Frame(r, e, "point2", "rotation2", body(j.body2));
  const std::string type = e.Text("type");
  using T = mech::TransformType;
  if (type == "rotational" || type == "translational") {
    const bool locked = r.Number(e, "locked", 0) != 0;
    const Vec3 axis = r.Vector(e, "axis", Vec3::UnitZ());
    j.chain.push_back(Dof(type == "rotational" ? T::kRv : T::kTv, axis, r.Number(e, "q0", 0), r.Number(e, "v0", 0),
                          locked, "", e.loc.str()));
  } else if (type == "fixed") {
  } else if (type == "cardan6") {
    const std::vector<double> q0 = r.Has(e, "q0") ? r.Numbers(e, "q0", 6) : std::vector<double>(6, 0.0);
    const std::vector<double> v0 = r.Has(e, "v0") ? r.Numbers(e, "v0", 6) : std::vector<double>(6, 0.0);
    const std::vector<double> off = r.Has(e, "locked") ? r.Numbers(e, "locked", 6) : std::vector<double>(6, 0.0);
    const char* names[6] = {"x", "y", "z", "rx", "ry", "rz"};
    for (int k = 0; k < 6; ++k)
      j.chain.push_back(Dof(k < 3 ? T::kTv : T::kRv, Vec3::Unit(k % 3), q0[k], v0[k], off[k] != 0,
                            j.name + "." + names[k], e.loc.str()));
  } else if (type == "quaternion") {
    j.quaternion = true;
    j.quaternion_initial.position = r.Vector(e, "position", Vec3::Zero());
    const Vec3 a = r.Vector(e, "angles", Vec3::Zero());
    j.quaternion_initial.orientation = Eigen::Quaterniond(mech::AxisRotation(Vec3::UnitX(), a.x()) *
                                                          mech::AxisRotation(Vec3::UnitY(), a.y()) *
                                                          mech::AxisRotation(Vec3::UnitZ(), a.z()));
    j.quaternion_initial.velocity = r.Vector(e, "velocity", Vec3::Zero());
    j.quaternion_initial.angular_velocity = r.Vector(e, "angular_velocity", Vec3::Zero());
  } else if (type == "convel") {
    j.convel = true;
    j.convel_axis1 = r.Vector(e, "axis1", Vec3::UnitZ());
    j.convel_axis2 = r.Vector(e, "axis2", Vec3::UnitZ());
    j.convel_reference1 = r.Vector(e, "reference1", Vec3::Zero());
    j.convel_reference2 = r.Vector(e, "reference2", Vec3::Zero());
  } else if (type == "generalized") {
    int k = 0;
    for (const ElementDesc& et : e.children) {
      ++k;
      const std::string what = et.loc.str() + ": joint '" + j.name + "' transformation " + std::to_string(k);
      const std::string et_type = et.Text("type");
      const auto it = std::find(kEtTypes.begin(), kEtTypes.end(), et_type);
      if (it == kEtTypes.end())
        throw InputError(what + ": unknown transformation type '" + et_type + "'" +
                         blocks::DidYouMean(et_type, kEtTypes) + "; expected one of " + blocks::JoinNames(kEtTypes));
      mech::TransformSpec spec;
      spec.type = static_cast<T>(it - kEtTypes.begin());
      spec.origin = et.loc.str();
      if (r.Has(et, "signal") && et_type != "tt" && et_type != "rt")
        throw InputError(what + ": 'signal' drives a prescribed transformation; use type \"tt\" or \"rt\"");
      if (et_type == "tc" && r.Has(et, "vector")) {
        const Vec3 vec = r.Vector(et, "vector", Vec3::Zero());
        if (!(vec.norm() > 0)) throw InputError(what + ": the translation vector is zero");
        spec.axis = vec;
        spec.value = vec.norm();
      } else {
        if (!r.Has(et, "axis")) throw InputError(what + ": needs 'axis' (\"x y z\")");
        spec.axis = r.Vector(et, "axis", Vec3::UnitX());
      }
      if (et_type == "tc" || et_type == "rc") {
        if (!r.Has(et, "vector")) spec.value = r.Number(et, "value", 0.0);
      } else if ((et_type == "tt" || et_type == "rt") && r.Has(et, "signal")) {
        // driven by a block signal: an input port of width 3 (q, q', q'')
        if (r.Has(et, "value")) throw InputError(what + ": give either 'value' (a function of t) or 'signal', not both");
        spec.signal = et.Text("signal");
        if (!scripting::IsLuaName(spec.signal))
          throw InputError(what + ": 'signal' must be a name (letters, digits, '_'), got '" + spec.signal + "'");
        if (std::find(r.inputs().begin(), r.inputs().end(), scripting::ToLower(spec.signal)) != r.inputs().end())
          throw InputError(what + ": the driving signal '" + spec.signal +
                           "' has the name of an <input>; a drive is its own port of q, q', q'' -- name it apart");
      } else if (et_type == "tt" || et_type == "rt") {
        if (!r.Has(et, "value"))
          throw InputError(what + ": needs 'value', a function of t, or 'signal', the name of a driving port");
        // a time function takes identifiers at their values at load: one
        // fed by a signal would stay at its start, silently
        if (r.MentionsInput(et.Text("value")))
          throw InputError(what + ": 'value' names an <input> of this mechanism (a signal), but a time function "
                                  "takes identifiers at their values at load and would not follow it; drive the "
                                  "motion by a signal instead (signal=\"NAME\", fed by a motion block)");
        r.CheckUnit(et, "value", false);
        spec.function = std::make_shared<scripting::JetExpression>(et.Text("value"), *eval.identifiers(), what);
        eval.identifiers()->NoteFixedUses(et.Text("value"), what);
      } else {
        spec.value = r.Number(et, "q0", 0.0);
        spec.rate = r.Number(et, "v0", 0.0);
        spec.locked = r.Number(et, "locked", 0.0) != 0;
        spec.dof_name = et.Text("name");
      }
      j.chain.push_back(spec);
    }
  } else {
    throw InputError(e.loc.str() + ": joint '" + j.name + "': unknown type '" + type + "'" +
                     blocks::DidYouMean(type, kJointTypes) + "; expected one of " + blocks::JoinNames(kJointTypes));
  }
  if (type != "generalized" && !e.children.empty())
    throw InputError(e.children[0].loc.str() + ": <et> belongs only in joints of type 'generalized'");
  return j;
}

std::unique_ptr<mech::ForceLaw> ReadLaw(const MechanismReader& r, const ElementDesc& e, double initial_x) {
  const std::string type = e.Text("type");
  if (type == "linear") {
    const mech::Parameter c = r.Param(e, "c", 0.0), d = r.Param(e, "d", 0.0);
    RequireAtLeast(r, e, "c", c, 0.0, "the stiffness c must not be negative");
    RequireAtLeast(r, e, "d", d, 0.0, "the damping d must not be negative");
    return std::make_unique<mech::LinearLaw>(c, r.Param(e, "x0", initial_x), d, r.Param(e, "f0", 0.0));
  }
  if (type == "points") {
    if (!r.Has(e, "points")) r.Fail(e, "a points law needs points=\"x1 F1; x2 F2; ...\"");
    std::vector<double> xs, fs;
    for (const auto& row : Split(e.Text("points"), ";")) {
      const std::vector<double> pair = r.eval().Numbers(row, r.What(e, "points"));
      if (pair.size() != 2) throw InputError(r.What(e, "points") + ": each point is 'x F'");
      xs.push_back(pair[0]);
      fs.push_back(pair[1]);
    }
    const std::string interp = e.Text("interpolation", "linear"), extrap = e.Text("extrapolation", "linear");
    if (interp != "linear" && interp != "spline") throw InputError(r.What(e, "interpolation") + ": linear or spline");
    if (extrap != "linear" && extrap != "clamp") throw InputError(r.What(e, "extrapolation") + ": linear or clamp");
    return std::make_unique<mech::PointsLaw>(
        xs, fs, interp == "spline" ? mech::PointsLaw::Interpolation::kSpline : mech::PointsLaw::Interpolation::kLinear,
        extrap == "clamp" ? mech::PointsLaw::Extrapolation::kClamp : mech::PointsLaw::Extrapolation::kLinear,
        r.Param(e, "d", 0.0), r.What(e, "points"));
  }
  if (type == "expression") {
    if (!r.Has(e, "expression")) r.Fail(e, "an expression law needs expression=\"...\" (of x, v, t)");
    return std::make_unique<mech::ExpressionLaw>(r.Function(e.Text("expression"), {"x", "v", "t"}, r.What(e, "expression")),
                                                 r.MentionsInput(e.Text("expression")));
  }
  const std::vector<std::string> laws = {"linear",     "points",           "expression",
                                         "frictional", "elastic_friction", "elastic_friction2"};
  throw InputError(r.What(e, "type") + ": unknown law '" + type + "'" + blocks::DidYouMean(type, laws) +
                   "; expected one of " + blocks::JoinNames(laws));
}

mech::BodySpec ReadBody(const MechanismReader& r, const ElementDesc& e) {
  mech::BodySpec b;
  b.name = e.Text("name");
  b.origin = e.loc.str();
  b.mass = r.Number(e, "mass", 0.0);
  b.com = r.Vector(e, "com", Vec3::Zero());
  const auto I = r.Numbers(e, "inertia", 3);
  const auto P = r.Has(e, "products") ? r.Numbers(e, "products", 3) : std::vector<double>(3, 0.0);
  b.inertia << I[0], P[0], P[1], P[0], I[1], P[2], P[1], P[2], I[2];
  for (const ElementDesc& p : e.children) b.points.push_back({p.Text("name"), r.Vector(p, "at", Vec3::Zero())});
  return b;
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
// joint coordinate (a friction moment there).
mech::FrictionalParameters ReadFrictional(const MechanismReader& r, const ElementDesc& e) {
  mech::FrictionalParameters p;
  const std::string stick = e.Text("stick", "spring");
  if (stick != "spring" && stick != "exact")
    throw InputError(r.What(e, "stick") + ": unknown stick model '" + stick +
                     "'; expected spring (held by the stiffness c and damping d) or exact (held by a constraint "
                     "force)");
  p.exact_stick = stick == "exact";
  if (p.exact_stick && (r.Has(e, "c") || r.Has(e, "d")))
    throw InputError(r.What(e, r.Has(e, "c") ? "c" : "d") +
                     ": with stick=\"exact\" the element is held by a constraint force, so a stick stiffness c "
                     "and damping d would have no effect; remove them, or use stick=\"spring\"");
  p.friction = r.Param(e, "friction", 0.0);
  p.ratio = r.Param(e, "ratio", 1.2);
  p.stiffness = r.Param(e, "c", 0.0);
  p.damping = r.Param(e, "d", 0.0);
  RequireAtLeast(r, e, "friction", p.friction, 0.0, "the friction force must not be negative");
  RequireAtLeast(r, e, "ratio", p.ratio, 1.0,
                 "the ratio of static to dynamic friction must be at least 1 (static below dynamic friction)");
  RequireAtLeast(r, e, "c", p.stiffness, 0.0, "the stiffness c must not be negative");
  RequireAtLeast(r, e, "d", p.damping, 0.0, "the damping d must not be negative");
  return p;
}

std::unique_ptr<mech::ForceElement> ReadElement(const MechanismReader& r, const ElementDesc& e,
                                                const mech::Model& model, const mech::Kinematics& kin0) {
  const std::string name = e.Text("name");
  if (r.Has(e, "stick") && e.Text("type") != "frictional")
    throw InputError(r.What(e, "stick") + ": only type=\"frictional\" has a stick model" +
                     (e.Text("type") == "elastic_friction" || e.Text("type") == "elastic_friction2"
                          ? std::string("; the slider of '") + e.Text("type") +
                                "' already sticks exactly (its stiffness is the elastic link in series)"
                          : std::string()));
  if (e.tag == "force") {
    const int b1 = BodyIndex(model, e, "body1"), b2 = BodyIndex(model, e, "body2");
    const Vec3 p1 = BodyPoint(r, model, e, "point1", b1), p2 = BodyPoint(r, model, e, "point2", b2);
    if (e.Text("type") == "frictional" || e.Text("type") == "elastic_friction") {
      const mech::FrictionalParameters p = ReadFrictional(r, e);
      if (e.Text("type") == "elastic_friction")
        return std::make_unique<mech::ElasticFrictionForce>(name, e.loc.str(), b1, p1, b2, p2, p);
      return std::make_unique<mech::FrictionalForce>(name, e.loc.str(), b1, p1, b2, p2, p);
    }
    if (e.Text("type") == "elastic_friction2") {
      mech::ElasticFriction2Parameters p;
      p.series_stiffness = r.Param(e, "c1", 0.0);
      p.parallel_stiffness = r.Param(e, "c2", 0.0);
      p.mu = r.Param(e, "mu", 0.0);
      p.mu0 = r.Has(e, "mu0") ? r.Param(e, "mu0", 0.0) : p.mu;
      p.free_length = r.Param(e, "l0", mech::BipolarLength(kin0, b1, p1, b2, p2));
      const std::string limit = e.Text("limit", "transmitted");
      const std::vector<std::string> limits = {"transmitted", "spring", "constant"};
      if (std::find(limits.begin(), limits.end(), limit) == limits.end())
        throw InputError(r.What(e, "limit") + ": unknown friction limit '" + limit + "'" +
                         blocks::DidYouMean(limit, limits) + "; expected one of " + blocks::JoinNames(limits));
      p.limit = limit == "spring" ? mech::FrictionLimit::kSpring
                : limit == "constant" ? mech::FrictionLimit::kConstant
                                      : mech::FrictionLimit::kTransmitted;
      if (p.limit == mech::FrictionLimit::kConstant && !r.Has(e, "normal_force"))
        r.Fail(e, "the constant friction limit needs normal_force (the limit is mu * normal_force)");
      p.normal_force = r.Param(e, "normal_force", 0.0);
      return std::make_unique<mech::ElasticFriction2Force>(name, e.loc.str(), b1, p1, b2, p2, p);
    }
    return std::make_unique<mech::BipolarForce>(name, e.loc.str(), b1, p1, b2, p2,
                                                ReadLaw(r, e, mech::BipolarLength(kin0, b1, p1, b2, p2)));
  }
  if (e.tag == "joint_force") {
    const mech::Dof& dof = model.dofs()[DofIndex(model, e, "dof")];
    if (e.Text("type") == "frictional")
      return std::make_unique<mech::FrictionalForce>(name, e.loc.str(), dof, ReadFrictional(r, e));
    if (e.Text("type") == "elastic_friction" || e.Text("type") == "elastic_friction2")
      throw InputError(r.What(e, "type") + ": '" + e.Text("type") +
                       "' acts between two body points (<force>); on a joint coordinate use type=\"frictional\" "
                       "(friction, ratio, and the stick stiffness c and damping d)");
    return std::make_unique<mech::JointForce>(name, e.loc.str(), dof, ReadLaw(r, e, model.initial_q()[dof.q_index]));
  }
  if (e.tag == "bushing") {
    const int b1 = BodyIndex(model, e, "body1"), b2 = BodyIndex(model, e, "body2");
    const Vec3 p1 = BodyPoint(r, model, e, "point1", b1);
    // Without point2: the point of body 2 that coincides with P1 initially.
    const Vec3 p2 = r.Has(e, "point2") ? BodyPoint(r, model, e, "point2", b2)
                                       : kin0.body_pose[b2].Inverse() * mech::PointPosition(kin0, b1, p1);
    mech::BushingParameters p;
    auto three = [&](const char* attribute, std::array<double, 3>* out) {
      if (!r.Has(e, attribute)) return;
      const Vec3 v = r.Vector(e, attribute, Vec3::Zero());
      for (int i = 0; i < 3; ++i)
        RequireAtLeast(r, e, attribute, v(i), 0.0, "stiffness and damping must not be negative");
      *out = {v.x(), v.y(), v.z()};
    };
    three("c", &p.stiffness);
    three("d", &p.damping);
    three("ca", &p.angular_stiffness);
    three("da", &p.angular_damping);
    p.preload_force = r.Vector(e, "preload", Vec3::Zero());
    p.preload_moment = r.Vector(e, "preload_moment", Vec3::Zero());
    return std::make_unique<mech::Bushing>(name, e.loc.str(), b1, p1, b2, p2, p, kin0);
  }
  if (e.tag == "gearing") {
    const int b1 = BodyIndex(model, e, "body1"), b2 = BodyIndex(model, e, "body2");
    mech::GearParameters p;
    p.ratio = r.Number(e, "ratio", 1.0);
    p.clearance = r.Number(e, "clearance", 0.0);
    p.stiffness = r.Number(e, "stiffness", 0.0);
    p.damping = r.Number(e, "damping", 0.0);
    // axis2 defaults to axis1's components (in gear 2's frame)
    const Vec3 axis1 = r.Vector(e, "axis1", Vec3::UnitX());
    return std::make_unique<mech::Gearing>(name, e.loc.str(), b1, BodyPoint(r, model, e, "centre1", b1), axis1, b2,
                                           BodyPoint(r, model, e, "centre2", b2), r.Vector(e, "axis2", axis1), p,
                                           kin0);
  }
  if (e.tag == "contact") {
    const std::string type = e.Text("type");
    if (type != "points_plane" && type != "circle_plane")
      throw InputError(r.What(e, "type") + ": unknown contact type '" + type + "'; expected points_plane or circle_plane");
    const int b1 = BodyIndex(model, e, "body1"), b2 = BodyIndex(model, e, "body2");
    mech::ContactLaw law;
    law.stiffness = r.Number(e, "stiffness", 0.0);
    law.exponent = r.Number(e, "exponent", 1.0);
    law.damping = r.Number(e, "damping", 0.0);
    law.damping_depth = r.Number(e, "damping_depth", 0.0);
    law.mu = r.Number(e, "mu", 0.0);
    law.mu_static = r.Has(e, "mu_static") ? r.Number(e, "mu_static", 0.0) : law.mu;
    law.stribeck_velocity = r.Number(e, "stribeck_velocity", 1e-3);
    law.v_eps = r.Number(e, "v_eps", 1e-4);
    law.max_penetration = r.Number(e, "max_penetration", mech::ContactLaw::kDefaultMaxPenetration);
    if (type == "circle_plane")
      return std::make_unique<mech::CirclePlaneContact>(
          name, e.loc.str(), b1, BodyPoint(r, model, e, "centre", b1), r.Vector(e, "circle_normal", Vec3::UnitX()),
          r.Number(e, "radius", 0.0), b2, r.Vector(e, "plane_point", Vec3::Zero()), r.Vector(e, "normal", Vec3::UnitZ()),
          law);
    std::vector<Vec3> points;
    for (const auto& row : Split(e.Text("points"), ";")) {
      r.eval().CheckUnit(row, true, "points", AttributeUnit(e.tag, type, "points"), r.What(e, "points"));
      const auto v = r.eval().Numbers(row, r.What(e, "points"));
      if (v.size() != 3) throw InputError(r.What(e, "points") + ": each point is 'x y z', separated by ';'");
      points.push_back({v[0], v[1], v[2]});
    }
    return std::make_unique<mech::PointsPlaneContact>(name, e.loc.str(), b1, points, b2,
                                                      r.Vector(e, "plane_point", Vec3::Zero()),
                                                      r.Vector(e, "normal", Vec3::UnitZ()), law);
  }
  // applied_force: components may follow inputs
  const int body = BodyIndex(model, e, "body");
  auto components = [&](const char* attribute) {
    std::array<mech::Parameter, 3> out{};
    if (!r.Has(e, attribute)) return out;
    const std::vector<std::string> parts = Split(e.Text(attribute), " \t,");
    if (parts.size() != 3) throw InputError(r.What(e, attribute) + ": expected three components");
    for (int i = 0; i < 3; ++i) {
      const std::string component = std::string(attribute) + "[" + std::to_string(i) + "]";
      ElementDesc one{e.tag, {{component, parts[i], e.Find(attribute)->loc}, {"name", name, e.loc}}, {}, e.loc};
      out[i] = r.Param(one, component, 0.0);
    }
    return out;
  };
  const std::string axes = e.Text("axes", "global");
  if (axes != "global" && axes != "body") throw InputError(r.What(e, "axes") + ": 'global' or 'body'");
  return std::make_unique<mech::AppliedForce>(name, e.loc.str(), body, BodyPoint(r, model, e, "point", body),
                                              components("force"), components("torque"), axes == "body");
}

const std::vector<std::string> kSensorKinds = {"coordinate", "velocity",       "acceleration",       "reaction_force",
                                               "reaction_torque", "element",   "position",           "point_velocity",
                                               "point_acceleration", "angles", "angular_velocity",
                                               "kinetic_energy",     "potential_energy", "energy_balance"};

mech::SensorSpec ReadSensor(const MechanismReader& r, const ElementDesc& e, const mech::Mechanism& mech) {
  const mech::Model& model = mech.model();
  mech::SensorSpec s;
  s.name = e.Text("name");
  s.origin = e.loc.str();
  const std::string kind = e.Text("kind");
  const auto it = std::find(kSensorKinds.begin(), kSensorKinds.end(), kind);
  if (it == kSensorKinds.end())
    throw InputError(r.What(e, "kind") + ": unknown sensor kind '" + kind + "'" + blocks::DidYouMean(kind, kSensorKinds) +
                     "; expected one of " + blocks::JoinNames(kSensorKinds));
  s.kind = static_cast<mech::SensorKind>(it - kSensorKinds.begin());
  switch (s.kind) {
    case mech::SensorKind::kCoordinate:
    case mech::SensorKind::kVelocity:
    case mech::SensorKind::kAcceleration:
      s.index = DofIndex(model, e, "dof");
      break;
    case mech::SensorKind::kReactionForce:
    case mech::SensorKind::kReactionTorque: {
      s.index = model.FindJoint(e.Text("joint"));
      if (s.index < 0) {
        std::vector<std::string> names;
        for (const auto& j : model.joints()) names.push_back(j.name);
        throw InputError(r.What(e, "joint") + ": unknown joint '" + e.Text("joint") + "'" +
                         blocks::DidYouMean(e.Text("joint"), names) + "; joints: " + blocks::JoinNames(names));
      }
      break;
    }
    case mech::SensorKind::kElement: {
      s.index = mech.FindElement(e.Text("element"));
      std::vector<std::string> names;
      for (int i = 0; i < mech.num_elements(); ++i) names.push_back(mech.element(i).name());
      if (s.index < 0)
        throw InputError(r.What(e, "element") + ": unknown element '" + e.Text("element") + "'" +
                         blocks::DidYouMean(e.Text("element"), names) + "; elements: " + blocks::JoinNames(names));
      const std::string quantity = e.Text("quantity", "force");
      s.element_sensor = mech.element(s.index).FindSensor(quantity);
      if (s.element_sensor < 0)
        throw InputError(r.What(e, "quantity") + ": element '" + e.Text("element") + "' has no output '" + quantity +
                         "'; it has " + blocks::JoinNames(mech.element(s.index).sensor_names()) +
                         (quantity == "dissipated" || quantity == "energy"
                              ? " (its stored energy is known only for linear laws and friction springs whose "
                                "stiffness, free length and preload are constants; use work)"
                              : ""));
      break;
    }
    case mech::SensorKind::kKineticEnergy:
    case mech::SensorKind::kPotentialEnergy:
      s.index = r.Has(e, "body") ? BodyIndex(model, e, "body") : -1;  // default: the whole mechanism
      break;
    case mech::SensorKind::kEnergyBalance:
      break;
    default:
      s.index = BodyIndex(model, e, "body");
      s.point = BodyPoint(r, model, e, "point", s.index);
  }
  if (r.Has(e, "component")) {
    const std::string c = e.Text("component");
    if (c != "x" && c != "y" && c != "z") throw InputError(r.What(e, "component") + ": x, y or z");
    s.component = c[0] - 'x';
  }
  return s;
}

}  // namespace

std::unique_ptr<blocks::Block> BuildMechanismBlock(const ElementDesc& m, const Evaluator& eval,
                                                   std::vector<std::string>* warnings) {
  const MechanismReader r(m, eval);
  mech::ModelBuilder builder;
  builder.SetGravity(r.Vector(m, "gravity", Vec3(0, 0, -9.81)));
  std::map<std::string, mech::BodySpec> bodies;  // by name, for the joints' frames
  for (const ElementDesc& e : m.children)
    if (e.tag == "body") {
      mech::BodySpec body = ReadBody(r, e);
      builder.AddBody(body);
      bodies.emplace(body.name, std::move(body));
    }
  for (const ElementDesc& e : m.children)
    if (e.tag == "joint") builder.AddJoint(ReadJoint(r, e, bodies, eval));
  const std::shared_ptr<const mech::Model> model = builder.Build();
  mech::Kinematics kin0(*model);
  const std::vector<double> v0(model->nv(), 0.0);
  mech::UpdateKinematics(*model, 0.0, model->initial_q(), v0, &kin0);
  std::vector<std::unique_ptr<mech::ForceElement>> elements;
  std::set<std::string> element_names;
  for (const ElementDesc& e : m.children) {
    if (e.tag != "force" && e.tag != "joint_force" && e.tag != "bushing" && e.tag != "applied_force" &&
        e.tag != "contact" && e.tag != "gearing")
      continue;
    if (!element_names.insert(e.Text("name")).second) r.Fail(e, "a second element with this name");
    elements.push_back(ReadElement(r, e, *model, kin0));
  }
  // Work and dissipation sensors need a state in their element, an energy
  // balance in every element (found by name through an index: a sensor per
  // element would otherwise search them all).
  std::map<std::string, mech::ForceElement*, std::less<>> element_by_name;
  for (auto& element : elements) element_by_name.emplace(element->name(), element.get());
  bool every_element_tracked = false;
  for (const ElementDesc& e : m.children) {
    if (e.tag != "sensor") continue;
    const std::string kind = e.Text("kind"), quantity = e.Text("quantity", "force");
    const bool balance = kind == "energy_balance";
    if (!balance && !(kind == "element" && (quantity == "work" || quantity == "dissipated"))) continue;
    if (balance) {
      if (!every_element_tracked)
        for (auto& element : elements) element->TrackWork();
      every_element_tracked = true;
    } else if (const auto it = element_by_name.find(e.Text("element")); it != element_by_name.end()) {
      it->second->TrackWork();
    }
  }
  std::vector<std::string> input_names;
  for (const ElementDesc& e : m.children)
    if (e.tag == "input") input_names.push_back(e.Text("name"));
  auto mechanism = std::make_shared<mech::Mechanism>(model, std::move(elements), input_names);
  const bool prescribed = std::any_of(model->segments().begin(), model->segments().end(),
                                      [](const mech::Segment& s) { return s.drive == mech::SegmentDrive::kTime; });
  for (const ElementDesc& e : m.children)
    if (e.tag == "sensor" && e.Text("kind") == "energy_balance" && prescribed) mechanism->TrackDriveWork();
  std::vector<mech::SensorSpec> sensors;
  for (const ElementDesc& e : m.children)
    if (e.tag == "sensor") sensors.push_back(ReadSensor(r, e, *mechanism));
  // Assemble once now, so that a loop that cannot close is bad input (exit 2)
  // rather than a failed run -- unless signals drive segments: their values
  // are known only once the diagram runs (the block assembles then).
  if (model->drive_signals().empty()) {
    mech::MechanismWorkspace ws(*mechanism);
    std::vector<double> x(mechanism->num_states()), modes(mechanism->num_modes());
    std::vector<double> inputs(mechanism->num_inputs(), 0.0);
    mech::InitialState(*mechanism, inputs, x, modes, &ws);
    // what the start says to check (a contact already beyond its bound
    // never crosses it, so the run would not warn)
    for (int e = 0; e < mechanism->num_elements(); ++e) {
      const mech::ForceElement& element = mechanism->element(e);
      const std::string warning = element.StartWarning(mech::MakeElementContext(*mechanism, 0.0, x, modes, ws, e));
      if (!warning.empty()) warnings->push_back(element.origin() + ": warning: " + warning);
    }
  }
  return std::make_unique<blocks::MechanismBlock>(m.Text("name"), mechanism, std::move(sensors));
}

}  // namespace mechflow::diagrams
