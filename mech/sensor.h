#pragma once
// Sensors: the named outputs of a mechanism (docs/ELEMENTS.md names each element's).
//
// A sensor reads the workspace after an evaluation. Positions, velocities and
// angles need only kinematics; accelerations, reactions and element sensors
// need the full evaluation (so in a diagram they depend directly on the
// mechanism's inputs). Body angles are the principal values: b in [-90, 90]
// deg, a and c in (-180, 180] deg, so a and c wrap when they pass 180 deg and
// the set is continuous otherwise as long as |b| < 90 deg.
// Vector sensors are 3 wide (global components) unless one component is
// chosen.

#include <span>
#include <string>

#include "mech/mechanism.h"

namespace mechflow::mech {

enum class SensorKind {
  kCoordinate,          // q of a DOF (index: Dof)
  kVelocity,            // v of a DOF
  kAcceleration,        // v' of a DOF
  kReactionForce,       // joint reaction force on body 2 (index: Joint), global
  kReactionTorque,      // joint reaction moment about body 2's attachment point, global
  kElement,             // element sensor (index: element, element_sensor)
  kPointPosition,       // body point (index: body, point in body frame), global
  kPointVelocity,
  kPointAcceleration,
  kBodyAngles,          // Cardan 1-2-3 angles of the body frame in the global frame [rad]
  kBodyAngularVelocity, // global components
  kKineticEnergy,       // of a body (index), or of the whole mechanism (index -1) [J]
  kPotentialEnergy,     // gravitational, -m g . r_com, zero at the global origin; body or mechanism [J]
  // Kinetic plus gravitational energy gained since the start minus the work
  // every element has done (each must TrackWork) and, with prescribed
  // motions, the work that drives them (Mechanism::TrackDriveWork): zero but
  // for the integration's error [J]
  kEnergyBalance
};

struct SensorSpec {
  std::string name;
  SensorKind kind = SensorKind::kCoordinate;
  int index = -1;
  int element_sensor = -1;
  Vec3 point = Vec3::Zero();
  int component = -1;  // vector sensors: -1 all three, 0..2 one of x, y, z
  std::string origin;
};

int SensorWidth(const SensorSpec& spec);
// Acceleration, reaction and point-acceleration sensors read the solved
// accelerations (they depend directly on the mechanism's inputs).
bool SensorNeedsAccelerations(const SensorSpec& spec);
// Those, and element sensors (written by the elements during
// EvaluateMechanism; an element's force may depend on the inputs through its
// parameters), need the full evaluation; the others only EvaluatePositions.
bool SensorNeedsFullEvaluation(const SensorSpec& spec);
// Coordinate and velocity sensors read the state alone.
bool SensorReadsStateOnly(const SensorSpec& spec);
// True when the sensor's value depends on the mechanism's inputs at the same
// instant: accelerations, reactions, and outputs of elements whose
// parameters follow inputs.
bool SensorDependsOnInputs(const Mechanism& mechanism, const SensorSpec& spec);
// Throws InputError (starting with spec.origin, naming the sensor) when the
// sensor's index, element sensor or component does not exist in `mechanism`.
void CheckSensor(const Mechanism& mechanism, const SensorSpec& spec);
// The SI unit of the sensor's values ("m", "rad/s", "N m", "J", "-" for
// modes; "" when unknown), for results files and plot labels.
std::string SensorUnit(const Mechanism& mechanism, const SensorSpec& spec);
// Writes the sensor's value(s). For acceleration/reaction sensors the
// workspace must hold a full EvaluateMechanism at the current state.
void EvaluateSensor(const Mechanism& mechanism, const MechanismWorkspace& ws, std::span<const double> x,
                    const SensorSpec& spec, std::span<double> out);

}  // namespace mechflow::mech
