#pragma once
// A force element with one stick/slip hold (mech/stick_slip.h) as its only
// modes and crossings: the three friction elements. It runs the mode machine
// -- crossings, their names, the switches at events and at rest -- from what
// the element measures of its hold; the element keeps its geometry, its
// springs, its states and its sensors.

#include <span>
#include <string>

#include "mech/force_element.h"
#include "mech/stick_slip.h"

namespace mechflow::mech {

class StickSlipElement : public ForceElement {
 public:
  static constexpr double kStick = StickSlip::kStick;

  void ZeroCrossings(const ElementContext& ctx, std::span<double> values) const final;
  void OnCrossing(int index, int direction, const ElementContext& ctx, std::span<double> state,
                  std::span<double> modes) const final;
  // A sliding element sticks as when its slip ends; a stuck one whose holding
  // force is beyond the static limit breaks away as at that crossing.
  bool ModesAtRest(const ElementContext& ctx, std::span<double> state, std::span<double> modes) const final;
  std::string CrossingName(int index, int direction) const final;

 protected:
  StickSlipElement(std::string name, std::string origin, StickSlip::Order order, StickSlip::Wording wording)
      : ForceElement(std::move(name), std::move(origin)), stick_slip_(order, 0, wording) {}
  // The mode and the hold's crossings; once, in the constructor.
  void DeclareStickSlip();

  // The hold measured in `mode` (ctx.modes may not be that mode). ctx.sensors,
  // when not empty, are the element's sensors on the same kinematics.
  virtual StickSlipHold Hold(const ElementContext& ctx, double mode) const = 0;
  // The mode switches from `from` to `to`, at an event, at rest or in a mode
  // update: reset the states the switch resets (ctx.modes still reads `from`).
  virtual void OnSwitch(const ElementContext& /*ctx*/, double /*from*/, double /*to*/,
                        std::span<double> /*state*/) const {}

  // Mode updates the elements choose from (ForceElement::UpdateModes); each
  // returns true when it switched. A stuck hold beyond its static limit slips
  // in its direction (exact stick, whose holding force jumps with the load).
  bool SlipWhereHoldFails(const ElementContext& ctx, std::span<double> state, std::span<double> modes) const;
  // A slip against its slip rate sticks (a break-away found where the force
  // only grazes its limit at a turning point).
  bool StickWhereSlipReverses(const ElementContext& ctx, std::span<double> state, std::span<double> modes) const;

 private:
  void Switch(const ElementContext& ctx, double to, std::span<double> state, std::span<double> modes) const;

  StickSlip stick_slip_;
};

}  // namespace mechflow::mech
