// Bodies and joints of a <mechanism> (diagrams/FORMAT.md, "Joints").

#include "diagrams/element_table.h"
#include "diagrams/mechanism_reader.h"
#include "scripting/jet_expression.h"

namespace mechflow::diagrams {
namespace {

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

const std::vector<std::string> kEtTypes = {"tc", "tt", "tv", "rc", "rt", "rv"};

}  // namespace

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
    const std::vector<std::string> types = FindElementSpec("joint")->VariantNames();  // the table's
    throw InputError(e.loc.str() + ": joint '" + j.name + "': unknown type '" + type + "'" +
                     blocks::DidYouMean(type, types) + "; expected one of " + blocks::JoinNames(types));
  }
  if (type != "generalized" && !e.children.empty())
    throw InputError(e.children[0].loc.str() + ": <et> belongs only in joints of type 'generalized'");
  return j;
}

}  // namespace mechflow::diagrams
