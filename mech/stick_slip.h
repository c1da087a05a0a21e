#pragma once
// One dry-friction hold along one direction: the stick/slip mode machine the
// friction elements share (docs/ELEMENTS.md 3.6-3.8).
//
//   modes: STICK (0), SLIP+ (+1, sliding forward), SLIP- (-1)
//   crossings, events (never `if`s inside a step):
//     SLIP+ -> STICK  when the slip rate falls through 0
//     SLIP- -> STICK  when the slip rate rises through 0
//     STICK -> SLIP+  when  H - limit rises through 0
//     STICK -> SLIP-  when -H - limit rises through 0
//   H, the holding force: what the stuck hold exerts against forward
//   sliding; limit: the law's static limit, never below 1e-9 N (a limit
//   that starts at exactly zero -- friction fed from a force that is zero at
//   the start -- must still give a crossing the solver can see: one that
//   starts at zero is not reported).
//
// An element measures its hold in a mode (StickSlipHold: its geometry, its
// springs, its law) and keeps its own states; this module turns the hold into
// the crossing values, names the crossings, and decides the modes at events,
// at the start and at rest. An inactive crossing sits at a constant on the
// side its function starts on when its mode begins, so entering a mode is no
// crossing.
//
// A contact point holds in its tangent plane: its two-component hold, with
// one break-away function (|H| - limit) and one slip-end function (the slip
// along its recorded direction), is mech/contact_stick.h; StickSlipHold and
// the decisions below are the 1-D case.

#include <array>
#include <span>
#include <string>

#include "mech/force_element.h"

namespace mechflow::mech {

// What an element measures of its hold in one mode.
struct StickSlipHold {
  bool active = true;         // false: switched off, no crossing can trigger
  double slip_rate = 0.0;     // the rate whose reversal ends a slip (sliding only)
  double holding = 0.0;       // H (stuck only)
  double static_limit = 0.0;  // the law's static limit, before the floor of 1e-9 N (stuck only)
};

class StickSlip {
 public:
  static constexpr double kStick = 0.0, kSlipForward = 1.0, kSlipBackward = -1.0;
  static constexpr int kNumCrossings = 4;
  // Where the four crossings stand among the element's (an element's order is
  // visible in `mechflow info` and kept).
  enum class Order { kSlipEndsFirst, kBreakawayFirst };
  // What the event log says: "<breaks>: slip+", "slip+ ends: <sticks>".
  struct Wording {
    const char* breaks;
    const char* sticks;
  };

  StickSlip(Order order, int first_crossing, Wording wording);

  // The directions of the four crossings, in the element's order.
  std::array<Crossing, kNumCrossings> Directions() const;
  bool Owns(int crossing) const { return crossing >= first_ && crossing < first_ + kNumCrossings; }
  int slip_forward_ends() const { return first_ + index_[0]; }
  int breaks_forward() const { return first_ + index_[2]; }
  int breaks_backward() const { return first_ + index_[3]; }

  // The mode at the start: sliding in the direction of the slip rate, stuck at rest.
  static double InitialMode(double slip_rate) {
    return slip_rate > 0 ? kSlipForward : slip_rate < 0 ? kSlipBackward : kStick;
  }
  // The mode crossing `crossing` (one of this hold's) switches to.
  double ModeAfter(int crossing) const;

  // The four crossing values (into values[first_crossing ...]) in `mode`.
  void ZeroCrossings(double mode, const StickSlipHold& hold, std::span<double> values) const;

  // Exact stick: a stuck hold whose H is beyond the static limit slips at once
  // in its direction (a load applied at once is held or not exactly). Returns
  // the mode to take: kStick when it holds.
  static double ModeOfHold(const StickSlipHold& hold);
  // A slip against its slip rate (a break-away found where the force only
  // grazes its limit at a turning point) should stick again.
  static bool SlipsBackwards(double mode, const StickSlipHold& hold) {
    return mode != kStick && !(mode * hold.slip_rate >= 0.0);
  }
  // The crossing that takes a hold to its mode at rest, or -1 for none: a
  // sliding hold sticks as when its slip ends; a stuck one whose H is beyond
  // the static limit breaks away in its direction. `hold` is measured in `mode`.
  int CrossingAtRest(double mode, const StickSlipHold& hold) const;

  std::string CrossingName(int crossing) const;
  // "sliding forward" / "sliding backward", for `mechflow modes`.
  static std::string Sliding(double mode) { return mode > 0 ? "sliding forward" : "sliding backward"; }

 private:
  int first_;
  // Among the four: slip+ ends, slip- ends, breaks forward, breaks backward.
  std::array<int, kNumCrossings> index_;
  Wording wording_;
};

}  // namespace mechflow::mech
