#include "mech/stick_slip_element.h"

namespace mechflow::mech {

void StickSlipElement::DeclareStickSlip() {
  DeclareModes(1);
  for (const Crossing direction : stick_slip_.Directions()) DeclareCrossing(direction);
}

void StickSlipElement::ZeroCrossings(const ElementContext& ctx, std::span<double> values) const {
  const double mode = ctx.modes[0];
  stick_slip_.ZeroCrossings(mode, Hold(ctx, mode), values);
}

void StickSlipElement::Switch(const ElementContext& ctx, double to, std::span<double> state,
                              std::span<double> modes) const {
  OnSwitch(ctx, modes[0], to, state);
  modes[0] = to;
}

void StickSlipElement::OnCrossing(int index, int, const ElementContext& ctx, std::span<double> state,
                                  std::span<double> modes) const {
  Switch(ctx, stick_slip_.ModeAfter(index), state, modes);
}

bool StickSlipElement::ModesAtRest(const ElementContext& ctx, std::span<double> state,
                                   std::span<double> modes) const {
  const double mode = modes[0];
  // measured only while stuck: a sliding hold sticks whatever it measures
  const int crossing = stick_slip_.CrossingAtRest(mode, mode == kStick ? Hold(ctx, mode) : StickSlipHold{});
  if (crossing < 0) return false;
  Switch(ctx, stick_slip_.ModeAfter(crossing), state, modes);
  return true;
}

std::string StickSlipElement::CrossingName(int index, int) const { return stick_slip_.CrossingName(index); }

bool StickSlipElement::SlipWhereHoldFails(const ElementContext& ctx, std::span<double> state,
                                          std::span<double> modes) const {
  if (modes[0] != kStick) return false;
  const double to = StickSlip::ModeOfHold(Hold(ctx, kStick));
  if (to == kStick) return false;
  Switch(ctx, to, state, modes);
  return true;
}

bool StickSlipElement::StickWhereSlipReverses(const ElementContext& ctx, std::span<double> state,
                                              std::span<double> modes) const {
  if (modes[0] == kStick || !StickSlip::SlipsBackwards(modes[0], Hold(ctx, modes[0]))) return false;
  Switch(ctx, kStick, state, modes);
  return true;
}

}  // namespace mechflow::mech
