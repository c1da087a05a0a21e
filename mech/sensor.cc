#include "mech/sensor.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "mech/errors.h"

namespace mechflow::mech {
namespace {

bool IsVector(SensorKind kind) {
  switch (kind) {
    case SensorKind::kReactionForce:
    case SensorKind::kReactionTorque:
    case SensorKind::kPointPosition:
    case SensorKind::kPointVelocity:
    case SensorKind::kPointAcceleration:
    case SensorKind::kBodyAngles:
    case SensorKind::kBodyAngularVelocity:
      return true;
    default:
      return false;
  }
}

// Cardan 1-2-3 angles (R = Rx(a) Ry(b) Rz(c)), continuous for |b| < 90 deg.
Vec3 CardanAngles(const Mat3& R) {
  const double b = std::asin(std::clamp(R(0, 2), -1.0, 1.0));
  const double a = std::atan2(-R(1, 2), R(2, 2));
  const double c = std::atan2(-R(0, 1), R(0, 0));
  return {a, b, c};
}

}  // namespace

int SensorWidth(const SensorSpec& spec) { return IsVector(spec.kind) && spec.component < 0 ? 3 : 1; }

bool SensorNeedsAccelerations(const SensorSpec& spec) {
  switch (spec.kind) {
    case SensorKind::kAcceleration:
    case SensorKind::kReactionForce:
    case SensorKind::kReactionTorque:
    case SensorKind::kPointAcceleration:
      return true;
    default:
      return false;
  }
}

bool SensorNeedsFullEvaluation(const SensorSpec& spec) {
  return SensorNeedsAccelerations(spec) || spec.kind == SensorKind::kElement;
}

bool SensorReadsStateOnly(const SensorSpec& spec) {
  return spec.kind == SensorKind::kCoordinate || spec.kind == SensorKind::kVelocity;
}

bool SensorDependsOnInputs(const Mechanism& mechanism, const SensorSpec& spec) {
  if (SensorNeedsAccelerations(spec)) return true;
  return spec.kind == SensorKind::kElement && mechanism.element(spec.index).depends_on_inputs();
}

void CheckSensor(const Mechanism& mechanism, const SensorSpec& spec) {
  const Model& model = mechanism.model();
  const std::string where = (spec.origin.empty() ? "" : spec.origin + ": ") + "sensor '" + spec.name + "'";
  auto in_range = [](int i, std::size_t n) { return i >= 0 && static_cast<std::size_t>(i) < n; };
  bool ok = true;
  const char* what = "";
  switch (spec.kind) {
    case SensorKind::kCoordinate:
    case SensorKind::kVelocity:
    case SensorKind::kAcceleration:
      ok = in_range(spec.index, model.dofs().size());
      what = "degree of freedom";
      break;
    case SensorKind::kReactionForce:
    case SensorKind::kReactionTorque:
      ok = in_range(spec.index, model.joints().size());
      what = "joint";
      break;
    case SensorKind::kElement:
      ok = in_range(spec.index, static_cast<std::size_t>(mechanism.num_elements()));
      what = "element";
      if (ok && !in_range(spec.element_sensor, static_cast<std::size_t>(mechanism.element(spec.index).num_sensors())))
        throw InputError(where + ": element '" + mechanism.element(spec.index).name() + "' has no output " +
                         std::to_string(spec.element_sensor));
      break;
    case SensorKind::kKineticEnergy:
    case SensorKind::kPotentialEnergy:
      ok = spec.index == -1 || in_range(spec.index, model.bodies().size());
      what = "body";
      break;
    case SensorKind::kEnergyBalance:
      for (int e = 0; e < mechanism.num_elements(); ++e)
        if (!mechanism.element(e).tracks_work())
          throw InputError(where + ": element '" + mechanism.element(e).name() + "' does not integrate its work");
      return;
    default:
      ok = in_range(spec.index, model.bodies().size());
      what = "body";
  }
  if (!ok) throw InputError(where + ": no " + what + " with index " + std::to_string(spec.index));
  if (spec.component < -1 || spec.component > 2)
    throw InputError(where + ": component " + std::to_string(spec.component) + " is not x, y or z");
}

void EvaluateSensor(const Mechanism& mechanism, const MechanismWorkspace& ws, std::span<const double> x,
                    const SensorSpec& spec, std::span<double> out) {
  const Model& model = mechanism.model();
  Vec3 value = Vec3::Zero();
  switch (spec.kind) {
    case SensorKind::kCoordinate:
      out[0] = x[model.dofs()[spec.index].q_index];
      return;
    case SensorKind::kVelocity:
      out[0] = x[model.nq() + model.dofs()[spec.index].v_index];
      return;
    case SensorKind::kAcceleration:
      out[0] = ws.vdot[model.dofs()[spec.index].v_index];
      return;
    case SensorKind::kElement:
      out[0] = ws.sensors[mechanism.sensor_offset(spec.index) + spec.element_sensor];
      return;
    case SensorKind::kReactionForce:
      value = JointReaction(mechanism, ws, spec.index).force;
      break;
    case SensorKind::kReactionTorque:
      value = JointReaction(mechanism, ws, spec.index).torque;
      break;
    case SensorKind::kPointPosition:
      value = PointPosition(ws.kin, spec.index, spec.point);
      break;
    case SensorKind::kPointVelocity:
      value = PointVelocity(ws.kin, spec.index, spec.point);
      break;
    case SensorKind::kPointAcceleration:
      value = PointAcceleration(model, ws.kin, ws.dyn, spec.index, spec.point);
      break;
    case SensorKind::kBodyAngles:
      value = CardanAngles(ws.kin.body_pose[spec.index].R);
      break;
    case SensorKind::kBodyAngularVelocity:
      value = ws.kin.body_omega[spec.index];
      break;
    case SensorKind::kKineticEnergy:
    case SensorKind::kPotentialEnergy: {
      const int first = spec.index < 0 ? 1 : spec.index, last = spec.index < 0 ? model.num_bodies() : spec.index + 1;
      double energy = 0.0;
      for (int b = first; b < last; ++b) energy += spec.kind == SensorKind::kKineticEnergy
                                                       ? KineticEnergy(model, ws.kin, b)
                                                       : PotentialEnergy(model, ws.kin, b);
      out[0] = energy;
      return;
    }
    case SensorKind::kEnergyBalance: {
      double balance = -ws.initial_mechanical_energy;
      for (int b = 1; b < model.num_bodies(); ++b)
        balance += KineticEnergy(model, ws.kin, b) + PotentialEnergy(model, ws.kin, b);
      for (int e = 0; e < mechanism.num_elements(); ++e)
        balance -= x[mechanism.state_offset(e) + mechanism.element(e).work_state()];
      if (mechanism.drive_work_state() >= 0) balance -= x[mechanism.drive_work_state()];
      out[0] = balance;
      return;
    }
  }
  if (spec.component >= 0) {
    out[0] = value(spec.component);
  } else {
    for (int i = 0; i < 3; ++i) out[i] = value(i);
  }
}

std::string SensorUnit(const Mechanism& mechanism, const SensorSpec& spec) {
  const Model& model = mechanism.model();
  const auto by_dof = [&](const char* translational, const char* rotational) {
    return std::string(model.dofs().at(spec.index).rotational ? rotational : translational);
  };
  switch (spec.kind) {
    case SensorKind::kCoordinate: return by_dof("m", "rad");
    case SensorKind::kVelocity: return by_dof("m/s", "rad/s");
    case SensorKind::kAcceleration: return by_dof("m/s^2", "rad/s^2");
    case SensorKind::kReactionForce: return "N";
    case SensorKind::kReactionTorque: return "N m";
    case SensorKind::kPointPosition: return "m";
    case SensorKind::kPointVelocity: return "m/s";
    case SensorKind::kPointAcceleration: return "m/s^2";
    case SensorKind::kBodyAngles: return "rad";
    case SensorKind::kBodyAngularVelocity: return "rad/s";
    case SensorKind::kKineticEnergy:
    case SensorKind::kPotentialEnergy:
    case SensorKind::kEnergyBalance: return "J";
    case SensorKind::kElement: break;
  }
  // an element on rotational coordinates (a joint force on a rotation)
  // measures moments and angles
  const ForceElement& element = mechanism.element(spec.index);
  bool rotational = !element.coordinates().empty();
  for (const int v : element.coordinates())
    for (const Dof& dof : model.dofs())
      if (dof.v_index == v && !dof.rotational) rotational = false;
  const std::string& name = element.sensor_names().at(spec.element_sensor);
  if (name == "force") return rotational ? "N m" : "N";
  if (name == "length" || name == "deflection") return rotational ? "rad" : "m";
  if (name == "rate") return rotational ? "rad/s" : "m/s";
  if (name == "normal" || name == "friction" || name == "fx" || name == "fy" || name == "fz") return "N";
  if (name == "mx" || name == "my" || name == "mz") return "N m";
  if (name == "penetration" || name == "dx" || name == "dy" || name == "dz") return "m";
  if (name == "slip") return "m/s";
  if (name == "ax" || name == "ay" || name == "az") return "rad";
  if (name == "energy" || name == "work" || name == "dissipated") return "J";
  if (name == "mode") return "-";
  return "";
}

}  // namespace mechflow::mech
