// The stick/slip module on its own (mech/stick_slip.h): the crossings' sign
// conventions (each fires, in its declared direction, exactly at the switch it
// names, and an inactive one cannot fire), the mode decisions at events, at the
// start, at rest and in mode updates, and the names the event log prints --
// in both crossing orders the friction elements use.

#include "mech/stick_slip.h"

#include <algorithm>
#include <array>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "mech/stick_slip_element.h"

namespace mechflow::mech {
namespace {

constexpr double kStick = StickSlip::kStick, kForward = StickSlip::kSlipForward, kBackward = StickSlip::kSlipBackward;
constexpr StickSlip::Wording kWording{"breaks", "sticks"};

StickSlipHold Stuck(double holding, double limit) { return {.holding = holding, .static_limit = limit}; }
StickSlipHold Sliding(double rate) { return {.slip_rate = rate}; }

// The crossing values of `hold` in `mode`, for a hold whose crossings start at
// `first` among six.
std::vector<double> Values(const StickSlip& s, double mode, const StickSlipHold& hold) {
  std::vector<double> values(6, 42.0);
  s.ZeroCrossings(mode, hold, values);
  return values;
}

// Whether `before` -> `after` is a crossing the solver reports in direction `d`.
bool Fires(Crossing d, double before, double after) {
  const bool rising = before < 0 && after >= 0, falling = before > 0 && after <= 0;
  return d == Crossing::kRising ? rising : d == Crossing::kFalling ? falling : rising || falling;
}

class StickSlipOrders : public ::testing::TestWithParam<StickSlip::Order> {
 protected:
  StickSlip s_{GetParam(), 1, kWording};
  int slip_backward_ends() const {
    for (int i = 1; i < 5; ++i)
      if (i != s_.slip_forward_ends() && i != s_.breaks_forward() && i != s_.breaks_backward()) return i;
    return -1;
  }
  Crossing Direction(int crossing) const { return s_.Directions()[crossing - 1]; }
};

TEST_P(StickSlipOrders, CrossingsAreTheFourAfterTheFirst) {
  EXPECT_FALSE(s_.Owns(0));
  EXPECT_FALSE(s_.Owns(5));
  const std::array<int, 4> mine{s_.slip_forward_ends(), slip_backward_ends(), s_.breaks_forward(),
                                s_.breaks_backward()};
  for (int i = 1; i < 5; ++i) {
    EXPECT_TRUE(s_.Owns(i));
    EXPECT_EQ(std::count(mine.begin(), mine.end(), i), 1) << i;
  }
  // only the hold's own values are written
  const std::vector<double> values = Values(s_, kStick, Stuck(0.0, 1.0));
  EXPECT_EQ(values[0], 42.0);
  EXPECT_EQ(values[5], 42.0);
}

TEST_P(StickSlipOrders, SlipEndsFireWhenTheSlipRateReverses) {
  const int fwd = s_.slip_forward_ends(), bwd = slip_backward_ends();
  EXPECT_TRUE(Fires(Direction(fwd), Values(s_, kForward, Sliding(0.1))[fwd], Values(s_, kForward, Sliding(-0.1))[fwd]));
  EXPECT_TRUE(
      Fires(Direction(bwd), Values(s_, kBackward, Sliding(-0.1))[bwd], Values(s_, kBackward, Sliding(0.1))[bwd]));
  // a slip that speeds up does not end
  EXPECT_FALSE(Fires(Direction(fwd), Values(s_, kForward, Sliding(0.1))[fwd], Values(s_, kForward, Sliding(0.2))[fwd]));
  EXPECT_EQ(s_.ModeAfter(fwd), kStick);
  EXPECT_EQ(s_.ModeAfter(bwd), kStick);
}

TEST_P(StickSlipOrders, BreakAwayFiresWhenTheHoldLeavesTheStaticLimit) {
  const int fwd = s_.breaks_forward(), bwd = s_.breaks_backward();
  const auto held = Values(s_, kStick, Stuck(0.9, 1.0));
  const auto pushed = Values(s_, kStick, Stuck(1.5, 1.0)), pulled = Values(s_, kStick, Stuck(-1.5, 1.0));
  EXPECT_TRUE(Fires(Direction(fwd), held[fwd], pushed[fwd]));
  EXPECT_FALSE(Fires(Direction(bwd), held[bwd], pushed[bwd]));
  EXPECT_TRUE(Fires(Direction(bwd), held[bwd], pulled[bwd]));
  EXPECT_FALSE(Fires(Direction(fwd), held[fwd], pulled[fwd]));
  EXPECT_EQ(pushed[fwd], 0.5);  // H - limit
  EXPECT_EQ(pulled[bwd], 0.5);  // -H - limit
  EXPECT_EQ(s_.ModeAfter(fwd), kForward);
  EXPECT_EQ(s_.ModeAfter(bwd), kBackward);
}

TEST_P(StickSlipOrders, AZeroLimitStillGivesACrossingTheSolverSees) {
  // friction fed from a force that is zero at the start: the break-away
  // functions start below zero, not at it
  const auto values = Values(s_, kStick, Stuck(0.0, 0.0));
  EXPECT_LT(values[s_.breaks_forward()], 0.0);
  EXPECT_LT(values[s_.breaks_backward()], 0.0);
  EXPECT_GT(values[s_.breaks_forward()], -1e-6);
}

TEST_P(StickSlipOrders, InactiveCrossingsSitWhereTheyStartWhenActive) {
  // An inactive function is a constant on the side its active value starts
  // on when its mode begins (a slip starts with the rate in its direction, a
  // stick within the limit), so entering a mode is no crossing -- whatever
  // the hold measures, and for every function of a switched-off hold.
  std::array<double, 6> start{};
  start[s_.slip_forward_ends()] = Values(s_, kForward, Sliding(1e-3))[s_.slip_forward_ends()];
  start[slip_backward_ends()] = Values(s_, kBackward, Sliding(-1e-3))[slip_backward_ends()];
  for (const int i : {s_.breaks_forward(), s_.breaks_backward()}) start[i] = Values(s_, kStick, Stuck(0.0, 1.0))[i];
  const StickSlipHold wild{.slip_rate = -5.0, .holding = 1e6, .static_limit = 0.0};
  const StickSlipHold off{.active = false, .slip_rate = -5.0, .holding = 1e6};
  for (const double mode : {kStick, kForward, kBackward}) {
    const auto values = Values(s_, mode, wild), dormant = Values(s_, mode, off);
    for (int i = 1; i < 5; ++i) {
      EXPECT_GT(dormant[i] * start[i], 0.0) << "switched off, crossing " << i;
      const bool active = (mode == kStick && (i == s_.breaks_forward() || i == s_.breaks_backward())) ||
                          (mode == kForward && i == s_.slip_forward_ends()) ||
                          (mode == kBackward && i == slip_backward_ends());
      if (!active) {
        EXPECT_GT(values[i] * start[i], 0.0) << "mode " << mode << ", crossing " << i;
      }
    }
  }
}

TEST_P(StickSlipOrders, AtRestASlideSticksAndAHoldBeyondItsLimitBreaksAway) {
  EXPECT_EQ(s_.CrossingAtRest(kForward, {}), s_.slip_forward_ends());
  EXPECT_EQ(s_.ModeAfter(s_.CrossingAtRest(kBackward, {})), kStick);
  EXPECT_EQ(s_.CrossingAtRest(kStick, Stuck(1.0, 1.0)), -1);  // at the limit: held
  EXPECT_EQ(s_.CrossingAtRest(kStick, Stuck(1.5, 1.0)), s_.breaks_forward());
  EXPECT_EQ(s_.CrossingAtRest(kStick, Stuck(-1.5, 1.0)), s_.breaks_backward());
  EXPECT_EQ(s_.CrossingAtRest(kStick, {.active = false, .holding = 1.5}), -1);
}

TEST_P(StickSlipOrders, NamesSayWhatTheSwitchMeans) {
  EXPECT_EQ(s_.CrossingName(s_.slip_forward_ends()), "slip+ ends: sticks");
  EXPECT_EQ(s_.CrossingName(slip_backward_ends()), "slip- ends: sticks");
  EXPECT_EQ(s_.CrossingName(s_.breaks_forward()), "breaks: slip+");
  EXPECT_EQ(s_.CrossingName(s_.breaks_backward()), "breaks: slip-");
}

INSTANTIATE_TEST_SUITE_P(BothOrders, StickSlipOrders,
                         ::testing::Values(StickSlip::Order::kSlipEndsFirst, StickSlip::Order::kBreakawayFirst),
                         [](const auto& info) {
                           return info.param == StickSlip::Order::kSlipEndsFirst ? "SlipEndsFirst" : "BreakawayFirst";
                         });

TEST(StickSlip, OrdersAreTheElementsOwn) {
  // `mechflow check` lists them: the Frictional element's slip ends come first,
  // the elastic-friction elements' break-aways
  using enum Crossing;
  EXPECT_EQ(StickSlip(StickSlip::Order::kSlipEndsFirst, 0, kWording).Directions(),
            (std::array<Crossing, 4>{kFalling, kRising, kRising, kRising}));
  EXPECT_EQ(StickSlip(StickSlip::Order::kBreakawayFirst, 0, kWording).Directions(),
            (std::array<Crossing, 4>{kRising, kRising, kFalling, kRising}));
}

TEST(StickSlip, ModeDecisions) {
  EXPECT_EQ(StickSlip::InitialMode(0.0), kStick);
  EXPECT_EQ(StickSlip::InitialMode(1e-300), kForward);
  EXPECT_EQ(StickSlip::InitialMode(-2.0), kBackward);
  // exact stick: held within the limit, else slips in the hold's direction
  EXPECT_EQ(StickSlip::ModeOfHold(Stuck(0.99, 1.0)), kStick);
  EXPECT_EQ(StickSlip::ModeOfHold(Stuck(-1.0, 1.0)), kStick);
  EXPECT_EQ(StickSlip::ModeOfHold(Stuck(1.01, 1.0)), kForward);
  EXPECT_EQ(StickSlip::ModeOfHold(Stuck(-1.01, 1.0)), kBackward);
  EXPECT_EQ(StickSlip::ModeOfHold(Stuck(1e-6, 0.0)), kForward);  // the floor is tiny
  // a slip against its slip rate
  EXPECT_TRUE(StickSlip::SlipsBackwards(kForward, Sliding(-0.1)));
  EXPECT_TRUE(StickSlip::SlipsBackwards(kBackward, Sliding(0.1)));
  EXPECT_FALSE(StickSlip::SlipsBackwards(kForward, Sliding(0.0)));
  EXPECT_FALSE(StickSlip::SlipsBackwards(kBackward, Sliding(-0.1)));
  EXPECT_FALSE(StickSlip::SlipsBackwards(kStick, Sliding(-0.1)));
  EXPECT_EQ(StickSlip::Sliding(kForward), "sliding forward");
  EXPECT_EQ(StickSlip::Sliding(kBackward), "sliding backward");
}

// An element that holds what the test says and records the switches.
class FakeHold final : public StickSlipElement {
 public:
  FakeHold() : StickSlipElement("fake", "", StickSlip::Order::kBreakawayFirst, kWording) { DeclareStickSlip(); }
  void Evaluate(const ElementContext&, Loads*, std::span<double>, std::span<double>) const override {}
  StickSlipHold Hold(const ElementContext&, double mode) const override {
    measured.push_back(mode);
    return hold;
  }
  void OnSwitch(const ElementContext& ctx, double from, double to, std::span<double> state) const override {
    EXPECT_EQ(ctx.modes[0], from);  // the switch sees the mode it leaves
    state[0] = 10 * from + to;
  }
  bool FailingHoldSlips(const ElementContext& ctx, std::span<double> state, std::span<double> modes) const {
    return SlipWhereHoldFails(ctx, state, modes);
  }
  bool ReversedSlipSticks(const ElementContext& ctx, std::span<double> state, std::span<double> modes) const {
    return StickWhereSlipReverses(ctx, state, modes);
  }
  StickSlipHold hold;
  mutable std::vector<double> measured;
};

struct FakeRun {
  FakeHold element;
  std::array<double, 1> state{-99.0}, modes{kStick};
  ElementContext ctx;
  FakeRun() { ctx.modes = modes; }
};

TEST(StickSlipElement, DeclaresOneModeAndTheFourCrossings) {
  FakeHold e;
  EXPECT_EQ(e.num_modes(), 1);
  ASSERT_EQ(e.num_crossings(), 4);
  EXPECT_EQ(e.crossing_direction(2), Crossing::kFalling);  // slip+ ends, break-aways first
  EXPECT_EQ(e.CrossingName(0, 1), "breaks: slip+");
}

TEST(StickSlipElement, EventsSwitchThroughTheElementsReset) {
  FakeRun r;
  r.element.OnCrossing(1, 1, r.ctx, r.state, r.modes);  // breaks backward
  EXPECT_EQ(r.modes[0], kBackward);
  EXPECT_EQ(r.state[0], -1.0);  // from 0 to -1
  r.element.OnCrossing(3, -1, r.ctx, r.state, r.modes);  // slip- ends
  EXPECT_EQ(r.modes[0], kStick);
  EXPECT_EQ(r.state[0], -10.0);
}

TEST(StickSlipElement, AtRestMeasuresOnlyAStuckHold) {
  FakeRun r;
  r.modes[0] = kForward;
  r.element.hold = Sliding(5.0);  // even sliding on: at rest it sticks
  EXPECT_TRUE(r.element.ModesAtRest(r.ctx, r.state, r.modes));
  EXPECT_EQ(r.modes[0], kStick);
  EXPECT_TRUE(r.element.measured.empty());
  r.element.hold = Stuck(0.5, 1.0);
  EXPECT_FALSE(r.element.ModesAtRest(r.ctx, r.state, r.modes));
  r.element.hold = Stuck(-2.0, 1.0);
  EXPECT_TRUE(r.element.ModesAtRest(r.ctx, r.state, r.modes));
  EXPECT_EQ(r.modes[0], kBackward);
  EXPECT_EQ(r.element.measured, (std::vector<double>{kStick, kStick}));
}

TEST(StickSlipElement, ModeUpdates) {
  FakeRun r;
  r.element.hold = Stuck(2.0, 1.0);
  EXPECT_FALSE(r.element.ReversedSlipSticks(r.ctx, r.state, r.modes));  // stuck: nothing to reverse
  EXPECT_TRUE(r.element.FailingHoldSlips(r.ctx, r.state, r.modes));
  EXPECT_EQ(r.modes[0], kForward);
  EXPECT_EQ(r.state[0], 1.0);
  EXPECT_FALSE(r.element.FailingHoldSlips(r.ctx, r.state, r.modes));  // sliding already
  r.element.hold = Sliding(0.3);
  EXPECT_FALSE(r.element.ReversedSlipSticks(r.ctx, r.state, r.modes));
  r.element.hold = Sliding(-0.3);
  EXPECT_TRUE(r.element.ReversedSlipSticks(r.ctx, r.state, r.modes));
  EXPECT_EQ(r.modes[0], kStick);
  EXPECT_EQ(r.state[0], 10.0);
}

TEST(StickSlipElement, CrossingsUseTheCurrentMode) {
  FakeRun r;
  r.modes[0] = kBackward;
  r.element.hold = Sliding(-0.25);
  std::array<double, 4> values{};
  r.element.ZeroCrossings(r.ctx, values);
  EXPECT_EQ(r.element.measured, (std::vector<double>{kBackward}));
  EXPECT_EQ(values[3], -0.25);  // slip- ends: the slip rate
}

}  // namespace
}  // namespace mechflow::mech
