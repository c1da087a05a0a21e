#include "blocks/library/motion.h"

#include <cmath>
#include <numbers>

namespace mechflow::blocks {

MotionSineBlock::MotionSineBlock(const std::string& name, double amplitude, double frequency, double phase,
                                 double bias)
    : Block("motion_sine", name),
      amplitude_(amplitude),
      omega_(2.0 * std::numbers::pi * frequency),
      phase_(phase),
      bias_(bias) {
  DeclareOutputPort("y", 3);
}

void MotionSineBlock::DoCalcOutput(int, const BlockContext& ctx) const {
  const double angle = omega_ * ctx.time() + phase_;
  const auto y = ctx.output(0);
  y[0] = bias_ + amplitude_ * std::sin(angle);
  y[1] = amplitude_ * omega_ * std::cos(angle);
  y[2] = -amplitude_ * omega_ * omega_ * std::sin(angle);
}

MotionTableBlock::MotionTableBlock(const std::string& name, Axis axis, std::vector<double> values, double start,
                                   double speed)
    : Block("motion_table", name),
      axis_(std::move(axis)),
      curve_(axis_, std::move(values)),
      modes_({&axis_}),
      start_(start),
      speed_(speed) {
  DeclareOutputPort("y", 3);
  DeclareDiscreteStates(modes_.num_modes());
  for (int i = 0; i < modes_.num_crossings(); ++i)
    DeclareZeroCrossing(AxisModes::CrossingRises(i) ? CrossingDirection::kRising : CrossingDirection::kFalling);
}

double MotionTableBlock::Argument(const BlockContext& ctx) const { return start_ + speed_ * ctx.time(); }

void MotionTableBlock::DoInitialize(const BlockContext& ctx) const { modes_.Initialize(ctx.discrete()); }

void MotionTableBlock::DoCalcOutput(int, const BlockContext& ctx) const {
  const double s = Argument(ctx);
  const CurvePoint p = curve_.At(axis_, s, modes_.Segment(0, s, ctx.discrete()));
  const auto y = ctx.output(0);
  y[0] = p.value;
  y[1] = speed_ * p.slope;
  y[2] = speed_ * speed_ * p.curvature;
}

void MotionTableBlock::DoCalcZeroCrossings(const BlockContext& ctx) const {
  const double s = Argument(ctx);
  modes_.Crossings({&s, 1}, ctx.discrete(), ctx.zero_crossings());
}

void MotionTableBlock::DoZeroCrossing(int index, int, const BlockContext& ctx) const {
  const double s = Argument(ctx);
  modes_.Cross(index, {&s, 1}, ctx.discrete());
}

bool MotionTableBlock::DoUpdateModes(const BlockContext& ctx) const {
  const double s = Argument(ctx);
  return modes_.Settle({&s, 1}, ctx.discrete());
}

MotionFilterBlock::MotionFilterBlock(const std::string& name, double frequency, double damping)
    : Block("motion_filter", name), omega_(2.0 * std::numbers::pi * frequency), damping_(damping) {
  DeclareInputPort("u");
  DeclareOutputPort("y", 3);
  DeclareContinuousStates(1, "q");
  DeclareContinuousStates(1, "v");
  DeclareDiscreteStates(1);  // 0 until the states start at u(t_start)
}

void MotionFilterBlock::DoInitialize(const BlockContext& ctx) const {
  ctx.state()[0] = ctx.state()[1] = 0.0;
  ctx.discrete()[0] = 0.0;
}

double MotionFilterBlock::Acceleration(const BlockContext& ctx) const {
  const auto x = ctx.state();
  return omega_ * omega_ * (ctx.input_scalar(0) - x[0]) - 2.0 * damping_ * omega_ * x[1];
}

void MotionFilterBlock::DoCalcOutput(int, const BlockContext& ctx) const {
  const auto y = ctx.output(0);
  y[0] = ctx.state()[0];
  y[1] = ctx.state()[1];
  y[2] = Acceleration(ctx);
}

void MotionFilterBlock::DoCalcDerivatives(const BlockContext& ctx) const {
  ctx.derivative()[0] = ctx.state()[1];
  ctx.derivative()[1] = Acceleration(ctx);
}

bool MotionFilterBlock::DoUpdateModes(const BlockContext& ctx) const {
  // the first update with a valid input: start at rest on it
  if (ctx.discrete()[0] != 0.0) return false;
  ctx.discrete()[0] = 1.0;
  ctx.state()[0] = ctx.input_scalar(0);
  ctx.state()[1] = 0.0;
  return true;
}

}  // namespace mechflow::blocks
