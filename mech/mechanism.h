#pragma once
// Mechanism: a compiled Model plus its force elements, evaluated as one
// first-order system for the integrator.
//
// State vector x = [q (nq) | v (nv) | element states]. Discrete modes and
// zero-crossings are the elements' own, concatenated in element order.
// Inputs are named scalars whose values come from outside every evaluation
// (identifier inputs, applied force components); elements see them through
// ElementContext::parameter_args = [t, inputs...].
//
// Accelerations: a tree is solved by the articulated-body algorithm, O(n);
// with cut joints the mass matrix and the constraint Jacobian form a KKT
// system solved through its Schur complement with damped pivots, so
// redundant and momentarily singular constraints are accepted
// (mech/constraint_solve.h).

#include <memory>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>
#include <Eigen/QR>

#include "mech/constraint_solve.h"
#include "mech/constraints.h"
#include "mech/dynamics.h"
#include "mech/exact_stick.h"
#include "mech/force_element.h"

namespace mechflow::mech {

class Mechanism {
 public:
  Mechanism(std::shared_ptr<const Model> model, std::vector<std::unique_ptr<ForceElement>> elements,
            std::vector<std::string> input_names);

  const Model& model() const { return *model_; }
  const std::shared_ptr<const Model>& model_ptr() const { return model_; }
  int num_elements() const { return static_cast<int>(elements_.size()); }
  const ForceElement& element(int i) const { return *elements_.at(i); }
  int FindElement(const std::string& name) const;
  int num_inputs() const { return static_cast<int>(input_names_.size()); }
  const std::string& input_name(int i) const { return input_names_.at(i); }
  int FindInput(const std::string& name) const;

  int num_states() const { return state_size_; }
  int num_modes() const { return mode_size_; }
  int num_crossings() const { return crossing_size_; }
  int num_sensor_values() const { return sensor_size_; }
  // Offsets of element i's slices.
  int state_offset(int i) const { return layout_.at(i).state; }
  int mode_offset(int i) const { return layout_.at(i).mode; }
  int crossing_offset(int i) const { return layout_.at(i).crossing; }
  int sensor_offset(int i) const { return layout_.at(i).sensor; }
  // Element i's holds (ForceElement::num_holds) among all of the mechanism's.
  int hold_offset(int i) const { return layout_.at(i).hold; }
  int num_holds() const { return static_cast<int>(hold_element_.size()); }
  int hold_element(int hold) const { return hold_element_[hold]; }
  const Constraints& constraints() const { return constraints_; }
  // The elements that can stick exactly (ForceElement::exact_stick): their
  // holding forces, and so their crossings, need the dynamics.
  const std::vector<int>& exact_stick_elements() const { return exact_stick_; }
  // True when some element integrates its work (ForceElement::TrackWork).
  bool tracks_work() const { return tracks_work_; }
  // Integrates the work that drives the prescribed (time-driven) motions,
  // the power the joints transmit along them, as one more state at the end
  // (for the energy balance). Call before any workspace or state exists.
  void TrackDriveWork();
  int drive_work_state() const { return drive_work_state_; }  // -1: not tracked

 private:
  struct Slices {
    int state, mode, crossing, sensor, hold;
  };
  std::shared_ptr<const Model> model_;
  std::vector<std::unique_ptr<ForceElement>> elements_;
  std::unordered_map<std::string, int> element_index_;  // name -> element (sensors of large models)
  std::vector<std::string> input_names_;
  std::vector<Slices> layout_;
  std::vector<int> exact_stick_;
  std::vector<int> hold_element_;  // per hold: its element
  bool tracks_work_ = false;
  int drive_work_state_ = -1;
  Constraints constraints_;
  int state_size_ = 0, mode_size_ = 0, crossing_size_ = 0, sensor_size_ = 0;
};

// Everything one evaluation needs, allocated once per mechanism and run.
struct MechanismWorkspace {
  explicit MechanismWorkspace(const Mechanism& mechanism);

  Kinematics kin;
  DynamicsWorkspace dyn;
  Loads loads;
  // While holds stick exactly: the loads of the elements without a stuck
  // hold, and of every element with the holding forces at zero.
  Loads loads_before_holds, loads_without_holds;
  ConstraintWorkspace constraint;
  StickWorkspace stick;
  std::vector<int> holding;            // the elements with a stuck hold in this evaluation
  std::vector<double> vdot;            // nv, after Evaluate
  std::vector<double> vdot_free;       // scratch nv: accelerations without holding forces
  std::vector<double> sensors;         // element sensor values, after Evaluate
  std::vector<std::uint64_t> sensors_on;  // per element: the kinematics' stamp its sensors were computed on
  std::vector<double> rates;           // scratch x' when the caller wants none
  std::vector<double> parameter_args;  // [t, inputs...]
  std::vector<std::unique_ptr<ElementScratch>> element_scratch;  // per element (null: it keeps none)
  // At the initial state: each element's stored energy (0 where it has
  // none) and the bodies' kinetic plus gravitational energy, the references
  // of the "dissipated" and energy_balance sensors.
  std::vector<double> initial_stored_energy;
  double initial_mechanical_energy = 0.0;
  bool accelerations_valid = false;
  // Set when reaction sensors are read: trees then also run Newton-Euler
  // after the articulated-body pass to get the transmitted forces.
  bool want_reactions = false;
};

// What element e reads at (t, x, modes) from the workspace's kinematics and
// parameters.
ElementContext MakeElementContext(const Mechanism& mechanism, double t, std::span<const double> x,
                                  std::span<const double> modes, const MechanismWorkspace& ws, int e);

// Initial state and modes: the model's initial coordinates, loops assembled
// (positions and velocities projected onto the constraints), elements
// initialised. Throws InputError when loops cannot be assembled or leave no
// motion, naming the joints and bodies.
void InitialState(const Mechanism& mechanism, std::span<const double> inputs, std::span<double> x,
                  std::span<double> modes, MechanismWorkspace* ws);

// Kinematics only (positions, velocities), for outputs that need no
// accelerations.
void EvaluatePositions(const Mechanism& mechanism, double t, std::span<const double> x, MechanismWorkspace* ws);

// Kinematics and the elements' loads, state rates and sensors, without the
// dynamics (for element outputs that do not depend on the inputs).
void EvaluateElements(const Mechanism& mechanism, double t, std::span<const double> x,
                      std::span<const double> inputs, std::span<const double> modes, MechanismWorkspace* ws,
                      std::span<double> xdot);

// The listed elements' sensors (and state rates, into the workspace) from the
// kinematics of EvaluatePositions at the same (t, x), for output rows and
// root checks that read element sensors and no loads: the workspace's loads
// are left incomplete.
void EvaluateSensedElements(const Mechanism& mechanism, double t, std::span<const double> x,
                            std::span<const double> inputs, std::span<const double> modes, MechanismWorkspace* ws,
                            std::span<const int> elements);

// Full evaluation: kinematics, element loads and sensors, the holding forces
// of the elements that stick exactly (mech/exact_stick.h), accelerations,
// constraint multipliers. Writes x' into `xdot` (may be empty to skip).
void EvaluateMechanism(const Mechanism& mechanism, double t, std::span<const double> x,
                       std::span<const double> inputs, std::span<const double> modes, MechanismWorkspace* ws,
                       std::span<double> xdot);

// True when some element sticks exactly in these modes: its holding force,
// and so its sensors and crossings, then need EvaluateMechanism.
bool AnyStuckExactly(const Mechanism& mechanism, double t, std::span<const double> x, std::span<const double> modes,
                     const MechanismWorkspace& ws);

// Kinematics and the parameters' arguments (t, inputs): all that the
// elements' zero crossings read, unless one sticks exactly (its holding force
// is EvaluateMechanism's).
void EvaluateForCrossings(const Mechanism& mechanism, double t, std::span<const double> x,
                          std::span<const double> inputs, MechanismWorkspace* ws);

// The elements' zero-crossing values after EvaluateForCrossings, EvaluateElements
// or EvaluateMechanism at the same (t, x).
void EvaluateCrossings(const Mechanism& mechanism, std::span<const double> x, std::span<const double> modes,
                       MechanismWorkspace* ws, std::span<double> values);

// An element crossing fired: let the element switch modes / reset states.
void ApplyCrossing(const Mechanism& mechanism, int crossing, int direction, std::span<double> x,
                   std::span<double> modes, MechanismWorkspace* ws);

// Lets every element reconcile its modes with the state (after an event or
// at the start); returns true when any mode (or state) changed. With
// exact-stick elements the mechanism is evaluated first (their holding
// forces decide whether they stay stuck), and again after every change
// until the modes agree; then ZeroStuckVelocities.
bool UpdateElementModes(const Mechanism& mechanism, double t, std::span<double> x, std::span<const double> inputs,
                        std::span<double> modes, MechanismWorkspace* ws);
// After a step: lets the elements turn the slip directions their modes
// record to the slips at (t, x) (ForceElement::FollowSlip).
void FollowSlips(const Mechanism& mechanism, double t, std::span<const double> x, std::span<double> modes,
                 MechanismWorkspace* ws);
// Moves the velocities in x the least (in the mass's norm) that brings
// every stuck hold's velocity to zero: the impulse p with S p = -w, which
// changes v by M^-1 J^T p (mech/exact_stick.h). A hold keeps a velocity
// constant, not zero: this removes what the root finder leaves of a slip
// that has just ended (~1e-12 m/s) at events, and the integrator's drift
// after steps. Needs no inputs. Returns true when it moved them.
bool ZeroStuckVelocities(const Mechanism& mechanism, double t, std::span<double> x, std::span<const double> modes,
                         MechanismWorkspace* ws);
// The same at a candidate rest state of a static equilibrium search: one
// pass of ForceElement::ModesAtRest (the search repeats its rounds itself,
// so that a friction element at rest sticking and breaking away again is a
// cycle it sees rather than a loop here).
bool ElementModesAtRest(const Mechanism& mechanism, double t, std::span<double> x, std::span<const double> inputs,
                        std::span<double> modes, MechanismWorkspace* ws);

// Reaction of joint j after EvaluateMechanism: the force and moment (global
// components, moment about the joint's attachment point on body 2) that body
// 1's side applies to body 2 through the joint.
struct Wrench {
  Vec3 force = Vec3::Zero();
  Vec3 torque = Vec3::Zero();
};
Wrench JointReaction(const Mechanism& mechanism, const MechanismWorkspace& ws, int joint);

}  // namespace mechflow::mech
