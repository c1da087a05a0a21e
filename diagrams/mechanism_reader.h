#pragma once
// What the readers of a <mechanism>'s elements share (diagrams/mechanism_loader.cc
// builds the block): the reader of attribute text into numbers, vectors and
// parameters, the lookups of bodies, points and coordinates, and the readers
// of each kind of element (bodies and joints, force elements, contacts,
// sensors), each in its own file.

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "blocks/support/suggest.h"
#include "diagrams/attribute_units.h"
#include "diagrams/description.h"
#include "diagrams/evaluator.h"
#include "mech/errors.h"
#include "mech/force_element.h"
#include "mech/force_law.h"
#include "mech/mechanism.h"
#include "mech/model_builder.h"
#include "mech/sensor.h"
#include "scripting/lua_scalar_function.h"

namespace mechflow::diagrams {

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
      // the name expressions know it by (an instance's parameter: its Lua name)
      inputs_.push_back(eval.identifiers()->name(eval.identifiers()->Find(name)));
    }
    // Expressions that follow inputs take them as arguments; Lua arguments may
    // not share a name with an identifier, so those expressions see the
    // identifiers without the inputs.
    const scripting::IdentifierTable& ids = *eval.identifiers();
    for (int i = 0; i < ids.size(); ++i) {
      if (std::find(inputs_.begin(), inputs_.end(), ids.name(i)) != inputs_.end()) continue;
      char value[32];
      std::snprintf(value, sizeof value, "%.17g", ids.value(i));
      non_inputs_.Add(ids.spelling(i), value, ids.origin(i));
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

// Bad input: a stiffness, damping or friction that is a constant below
// `minimum` is an error at the attribute's file:line. Parameters that follow
// inputs are checked by their elements at run time.
void RequireAtLeast(const MechanismReader& r, const ElementDesc& e, const std::string& attribute,
                    const mech::Parameter& p, double minimum, const std::string& what);

// A frame on a body: `point` ("x y z" or a point's name) and `rotation`
// (Cardan 1-2-3 [rad]).
mech::Pose Frame(const MechanismReader& r, const ElementDesc& e, const std::string& point,
                 const std::string& rotation, const mech::BodySpec* body);

// The body, point or coordinate an attribute names; an unknown name is bad
// input naming the valid ones.
int BodyIndex(const mech::Model& model, const ElementDesc& e, const std::string& attribute);
Vec3 BodyPoint(const MechanismReader& r, const mech::Model& model, const ElementDesc& e, const std::string& attribute,
               int body);
int DofIndex(const mech::Model& model, const ElementDesc& e, const std::string& attribute);

// diagrams/joint_reader.cc
mech::BodySpec ReadBody(const MechanismReader& r, const ElementDesc& e);
mech::JointSpec ReadJoint(const MechanismReader& r, const ElementDesc& e,
                          const std::map<std::string, mech::BodySpec>& bodies, const Evaluator& eval);
// diagrams/force_element_reader.cc: <force>, <joint_force>, <bushing>,
// <gearing>, <applied_force>, and <contact> through ReadContact.
std::unique_ptr<mech::ForceElement> ReadElement(const MechanismReader& r, const ElementDesc& e,
                                                const mech::Model& model, const mech::Kinematics& kin0);
// diagrams/contact_reader.cc
std::unique_ptr<mech::ForceElement> ReadContact(const MechanismReader& r, const ElementDesc& e,
                                                const mech::Model& model);
// diagrams/sensor_reader.cc
mech::SensorSpec ReadSensor(const MechanismReader& r, const ElementDesc& e, const mech::Mechanism& mech);

}  // namespace mechflow::diagrams
