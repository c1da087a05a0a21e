#pragma once
// ElementDriveBlock: one force element of a mechanism, detached from the
// rest and driven along its own scalar coordinate (ForceElement::Coordinate)
// as x = x0 + a sin(2 pi f t + phase) -- the harmonic drive of force analysis (the
// seed's "Analysis of force elements", docs/ELEMENTS.md 3.10).
//
// x0 is the coordinate in the diagram's initial configuration. Every body
// is held there at rest except the one the drive moves: body 2 along the
// line (body 1 when body 2 is the ground), body 1 into a contact plane,
// body 2 along or about a bushing axis; a joint coordinate is set directly.
// The element's own states, modes and events run as the block's, so a
// friction element sticks and slips as it would in the mechanism.
//
// Outputs (scalars): "x" the imposed change x - x0, "v" its rate, "force"
// the element's force along the coordinate (positive pushes it up) and
// "reaction" = -force, what it takes to impose the motion. The mechanism
// must outlive the block.

#include <memory>
#include <string>
#include <vector>

#include "blocks/framework/block.h"
#include "mech/mechanism.h"

namespace mechflow::analysis {

struct HarmonicDrive {
  double amplitude = 0.0;  // [m] or [rad]
  double frequency = 0.0;  // [Hz], > 0
  double phase = 0.0;      // [rad]: x = x0 + a sin(2 pi f t + phase)
};

class ElementDriveBlock final : public blocks::Block {
 public:
  // Throws InputError saying why when the element cannot be driven alone:
  // no scalar coordinate (or an unknown component), parameters that follow
  // signal inputs, an exact stick (no force of its own while it sticks), a
  // line of zero length or between two ground bodies.
  ElementDriveBlock(std::string name, const mech::Mechanism& mechanism, int element, const std::string& component,
                    HarmonicDrive drive);

  double initial_coordinate() const { return x0_; }
  std::unique_ptr<blocks::BlockScratch> MakeScratch() const override;

 private:
  struct Scratch;  // the run's kinematics and element buffers

  void DoInitialize(const blocks::BlockContext& ctx) const override;
  void DoCalcOutput(int port, const blocks::BlockContext& ctx) const override;
  void DoCalcDerivatives(const blocks::BlockContext& ctx) const override;
  void DoCalcZeroCrossings(const blocks::BlockContext& ctx) const override;
  void DoZeroCrossing(int index, int direction, const blocks::BlockContext& ctx) const override;
  bool DoUpdateModes(const blocks::BlockContext& ctx) const override;

  // The element's context at time t with the drive applied (kinematics and
  // coordinates in the run's scratch `s`); `driven` false: at rest at x0.
  mech::ElementContext Context(Scratch& s, double t, std::span<const double> state, std::span<const double> modes,
                               bool driven = true) const;
  // Element sensors at the block's current state, into s.sensors.
  void Evaluate(const blocks::BlockContext& ctx, Scratch& s, std::span<double> rates) const;

  const mech::Mechanism& mechanism_;
  const mech::ForceElement& element_;
  mech::ElementCoordinate coordinate_;
  HarmonicDrive drive_;
  double x0_ = 0.0;
  int mover_ = -1;                           // the body the drive moves
  mech::Vec3 direction_ = mech::Vec3::Zero();            // global: translation, or rotation axis
  mech::Vec3 pivot_ = mech::Vec3::Zero();                // global point on a rotation axis
  mech::Kinematics kin0_;                    // the initial configuration, at rest
  std::vector<double> q0_;
};

}  // namespace mechflow::analysis
