#include "mech/stick_slip.h"

#include <cmath>

namespace mechflow::mech {
namespace {

enum Role { kSlipForwardEnds, kSlipBackwardEnds, kBreaksForward, kBreaksBackward };

// The static limit with its floor (see the header).
double BreakawayLimit(double limit) { return limit > 1e-9 ? limit : 1e-9; }

}  // namespace

StickSlip::StickSlip(Order order, int first_crossing, Wording wording)
    : first_(first_crossing),
      index_(order == Order::kSlipEndsFirst ? std::array<int, kNumCrossings>{0, 1, 2, 3}
                                            : std::array<int, kNumCrossings>{2, 3, 0, 1}),
      wording_(wording) {}

std::array<Crossing, StickSlip::kNumCrossings> StickSlip::Directions() const {
  std::array<Crossing, kNumCrossings> directions{};
  directions[index_[kSlipForwardEnds]] = Crossing::kFalling;  // slip rate
  directions[index_[kSlipBackwardEnds]] = Crossing::kRising;  // slip rate
  directions[index_[kBreaksForward]] = Crossing::kRising;     // H - limit
  directions[index_[kBreaksBackward]] = Crossing::kRising;    // -H - limit
  return directions;
}

double StickSlip::ModeAfter(int crossing) const {
  const int local = crossing - first_;
  if (local == index_[kBreaksForward]) return kSlipForward;
  if (local == index_[kBreaksBackward]) return kSlipBackward;
  return kStick;
}

void StickSlip::ZeroCrossings(double mode, const StickSlipHold& hold, std::span<double> values) const {
  double* v = values.data() + first_;
  if (!hold.active) {
    v[index_[kSlipForwardEnds]] = 1.0;
    v[index_[kSlipBackwardEnds]] = v[index_[kBreaksForward]] = v[index_[kBreaksBackward]] = -1.0;
    return;
  }
  v[index_[kSlipForwardEnds]] = mode == kSlipForward ? hold.slip_rate : 1.0;
  v[index_[kSlipBackwardEnds]] = mode == kSlipBackward ? hold.slip_rate : -1.0;
  const double limit = BreakawayLimit(hold.static_limit);
  v[index_[kBreaksForward]] = mode == kStick ? hold.holding - limit : -1.0;
  v[index_[kBreaksBackward]] = mode == kStick ? -hold.holding - limit : -1.0;
}

double StickSlip::ModeOfHold(const StickSlipHold& hold) {
  if (!hold.active || std::abs(hold.holding) <= BreakawayLimit(hold.static_limit)) return kStick;
  return hold.holding > 0 ? kSlipForward : kSlipBackward;
}

int StickSlip::CrossingAtRest(double mode, const StickSlipHold& hold) const {
  if (mode != kStick) return slip_forward_ends();
  if (!hold.active) return -1;
  const double limit = BreakawayLimit(hold.static_limit);
  if (hold.holding - limit > 0) return breaks_forward();
  if (-hold.holding - limit > 0) return breaks_backward();
  return -1;
}

std::string StickSlip::CrossingName(int crossing) const {
  const int local = crossing - first_;
  if (local == index_[kSlipForwardEnds]) return std::string("slip+ ends: ") + wording_.sticks;
  if (local == index_[kSlipBackwardEnds]) return std::string("slip- ends: ") + wording_.sticks;
  if (local == index_[kBreaksForward]) return std::string(wording_.breaks) + ": slip+";
  if (local == index_[kBreaksBackward]) return std::string(wording_.breaks) + ": slip-";
  return "crossing " + std::to_string(crossing);
}

}  // namespace mechflow::mech
