#pragma once
// MechanismBlock: a multibody mechanism as one block of a diagram.
//
//   inputs:  one scalar port per mechanism input (identifier inputs, applied
//            force components), named as the mechanism names them; then one
//            port of width 3 (q, q', q'') per driving signal of a segment
//            (mech::Model::drive_signals), named after the signal
//   outputs: one port per sensor (width 1, or 3 for vector sensors)
//   states:  the mechanism's state vector ("q:<dof>", "v:<dof>", quaternion
//            joints "<joint>.x" ..., element states "<element>.s<k>"), its
//            elements' modes as discrete states, their crossings as zero
//            crossings
//
// Feedthrough is declared per sensor: positions, velocities and angles come
// from the state alone, so they may feed back into the same mechanism without
// an algebraic loop; accelerations, reactions and element forces depend on
// the inputs at the same instant.
//
// Closed loops and quaternion joints declare a projection: after every solver
// step the positions are moved back onto the loop constraints (Gauss-Newton,
// least-norm steps), the velocities onto their tangent, and quaternions are
// normalised. The residual norms seen at projections are kept for reports.
//
// Sensors are checked against the mechanism at construction (InputError for
// an index that does not exist or a repeated sensor name).
//
// Initialize runs mech::InitialState with every input at zero: inputs are not
// valid yet when a diagram initialises (blocks/framework/block.h), so elements whose
// initial state depends on an input see it as zero. A mechanism with driving
// signals runs it again at its first mode update, when the inputs are valid:
// loops assemble around the drives' starting positions.
//
// Each run keeps a workspace in its Context (the block's scratch, so one
// block may be run by several Contexts at once), shared within one evaluation
// (Context::evaluation) between the block's output ports, its derivatives and
// its zero crossings: the mechanism is solved at most once per evaluation,
// and only its kinematics when every port read is a position, velocity or
// angle.

#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "blocks/framework/block.h"
#include "mech/sensor.h"
#include "mech/sliding_jacobian.h"

namespace mechflow::blocks {

class MechanismBlock final : public Block {
 public:
  MechanismBlock(std::string name, std::shared_ptr<const mech::Mechanism> mechanism,
                 std::vector<mech::SensorSpec> sensors);

  const mech::Mechanism& mechanism() const { return *mechanism_; }
  // Largest position-constraint residual (max norm) seen before projection
  // during the run that `run` holds, and at its last projection after it;
  // `block` is this block's index in the diagram.
  double worst_constraint_residual(const Context& run, int block) const;

  // From the topology, found on first use (once, whichever thread asks
  // first): for a long serial chain the pattern is dense, and `mechflow
  // check` should not pay for it.
  const BlockSparsity* sparsity() const override;
  // Names the loop constraint that became dependent when the run failed at
  // a singular position.
  std::string FailureNote(const BlockContext& ctx) const override;
  std::unique_ptr<BlockScratch> MakeScratch() const override;
  // "element: what its crossing meant" (mech::ForceElement::CrossingName)
  std::string CrossingName(int index, int direction) const override;
  std::string OutputUnit(int port) const override { return mech::SensorUnit(*mechanism_, sensors_.at(port)); }
  // A sliding mechanism's (mech/sliding_jacobian.h).
  std::string StateJacobianUnavailable() const override;
  void CalcStateJacobian(const BlockContext& ctx, std::vector<JacobianEntry>* entries) const override;

 private:
  void DoInitialize(const BlockContext& ctx) const override;
  void DoCalcOutput(int port, const BlockContext& ctx) const override;
  void DoCalcDerivatives(const BlockContext& ctx) const override;
  void DoCalcZeroCrossings(const BlockContext& ctx) const override;
  void DoZeroCrossing(int index, int direction, const BlockContext& ctx) const override;
  bool DoUpdateModes(const BlockContext& ctx) const override;
  bool DoUpdateModesAtRest(const BlockContext& ctx) const override;
  void DoProject(const BlockContext& ctx, std::span<double> correction, std::span<double> error,
                 std::span<const double> weights) const override;

  // The run's workspace and caches (defined in the .cc).
  struct Scratch;

  // The scalar inputs; also copies the driving signals into the kinematics.
  std::span<const double> Inputs(const BlockContext& ctx, Scratch& s) const;
  void ReadDrives(const BlockContext& ctx, Scratch& s) const;
  void EnsureEvaluated(const BlockContext& ctx, Scratch& s, bool full) const;
  // The elements' loads and sensors without the dynamics, with every input
  // computed (once per evaluation).
  void EvaluateElementsWithInputs(const BlockContext& ctx, Scratch& s) const;
  // The kinematics and the elements that sensors read, for output rows and
  // root checks (once per evaluation); `inputs_computed`: every input is
  // computed by now, else only elements that read none may be read.
  void EvaluateSensedElements(const BlockContext& ctx, Scratch& s, bool inputs_computed) const;
  // Some element sticks exactly: its holding force needs the dynamics.
  bool StuckExactly(const BlockContext& ctx, const Scratch& s) const;

  // What an output port evaluates, fixed by its sensor (DoCalcOutput).
  enum class PortRoute : std::uint8_t {
    kState,                // nothing: it reads the state
    kElementBeforeInputs,  // the sensed elements, which read no input (the inputs may not be computed yet)
    kElement,              // the sensed elements, or the solve when derivatives follow or an element sticks exactly
    kPositions,            // the kinematics
    kSolve,                // the dynamics (accelerations, reactions)
  };
  PortRoute RouteOf(const mech::SensorSpec& sensor) const;

  std::shared_ptr<const mech::Mechanism> mechanism_;
  std::vector<mech::SensorSpec> sensors_;
  std::vector<PortRoute> routes_;     // per output port
  // Per output port: where its scalar value is read, for the sensors that
  // only copy one (coordinates and velocities: the state's index; element
  // sensors: the workspace's sensor index); -1 for the others.
  std::vector<int> slots_;
  std::vector<int> sensed_elements_;  // the elements an element sensor reads, in order
  bool want_reactions_ = false;       // a reaction sensor is read (MechanismWorkspace::want_reactions)
  // Structure found on first use; call_once makes that safe from any thread.
  mutable std::once_flag sparsity_once_;
  mutable std::optional<BlockSparsity> sparsity_;
  std::optional<mech::SlidingJacobian> jacobian_;  // a sliding mechanism's
};

}  // namespace mechflow::blocks
