#include "mech/sensor.h"

#include <algorithm>
#include <cmath>

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
    case SensorKind::kElement:  // element forces may depend on inputs
      return true;
    default:
      return false;
  }
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
  }
  if (spec.component >= 0) {
    out[0] = value(spec.component);
  } else {
    for (int i = 0; i < 3; ++i) out[i] = value(i);
  }
}

}  // namespace mechflow::mech
