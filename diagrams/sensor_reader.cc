// Sensors of a <mechanism>: its output ports (diagrams/FORMAT.md, "Sensors").

#include "diagrams/mechanism_reader.h"

namespace mechflow::diagrams {
namespace {

const std::vector<std::string> kSensorKinds = {"coordinate", "velocity",       "acceleration",       "reaction_force",
                                               "reaction_torque", "element",   "position",           "point_velocity",
                                               "point_acceleration", "angles", "angular_velocity",
                                               "kinetic_energy",     "potential_energy", "energy_balance"};

}  // namespace

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

}  // namespace mechflow::diagrams
