#pragma once
// Source blocks: outputs that depend on time only (no inputs).
//
//   constant  y = value                               (width = number of values)
//   clock     y = t
//   step      y = before for t < time, after for t >= time
//   ramp      y = initial for t < start, initial + slope (t - start) after
//   sine      y = bias + amplitude sin(2 pi frequency t + phase)   [Hz, rad]
//   table     y = piecewise-linear interpolation of (t_i, y_i), held constant
//             beyond the first and last points
//
// The step and the corner of the ramp are events: a zero crossing t - time
// switches a mode, and the output follows the mode, so the solver never steps
// across the discontinuity. The corners of a table are not events (the output
// is continuous); bound the step with max_step if a table has sharp corners.

#include <vector>

#include "blocks/block.h"

namespace mechflow::blocks {

class ConstantBlock : public Block {
 public:
  ConstantBlock(const std::string& name, std::vector<double> value);

 protected:
  void DoCalcOutput(int port, const BlockContext& ctx) const override;

 private:
  std::vector<double> value_;
};

class ClockBlock : public Block {
 public:
  explicit ClockBlock(const std::string& name);

 protected:
  void DoCalcOutput(int port, const BlockContext& ctx) const override;
};

// A value that switches at one instant: the step, and the ramp's corner.
class SwitchAtTimeBlock : public Block {
 public:
  SwitchAtTimeBlock(const std::string& type, const std::string& name, double switch_time);

 protected:
  bool switched(const BlockContext& ctx) const { return ctx.discrete()[0] != 0.0; }
  double switch_time() const { return switch_time_; }
  void DoInitialize(const BlockContext& ctx) const override;
  void DoCalcZeroCrossings(const BlockContext& ctx) const override;
  void DoZeroCrossing(int index, int direction, const BlockContext& ctx) const override;
  bool DoUpdateModes(const BlockContext& ctx) const override;

 private:
  double switch_time_;
};

class StepBlock : public SwitchAtTimeBlock {
 public:
  StepBlock(const std::string& name, double time, double before, double after);

 protected:
  void DoCalcOutput(int port, const BlockContext& ctx) const override;

 private:
  double before_, after_;
};

class RampBlock : public SwitchAtTimeBlock {
 public:
  RampBlock(const std::string& name, double slope, double start, double initial);

 protected:
  void DoCalcOutput(int port, const BlockContext& ctx) const override;

 private:
  double slope_, initial_;
};

class SineBlock : public Block {
 public:
  SineBlock(const std::string& name, double amplitude, double frequency, double phase, double bias);

 protected:
  void DoCalcOutput(int port, const BlockContext& ctx) const override;

 private:
  double amplitude_, omega_, phase_, bias_;
};

class TableBlock : public Block {
 public:
  // `times` strictly increasing, at least two points (checked by the factory).
  TableBlock(const std::string& name, std::vector<double> times, std::vector<double> values);

 protected:
  void DoCalcOutput(int port, const BlockContext& ctx) const override;

 private:
  std::vector<double> times_, values_;
};

// Reads a two-column CSV (t, y): commas or whitespace, '#' comments, one
// optional non-numeric header line. Throws InputError naming path:line.
void ReadTableCsv(const std::string& path, std::vector<double>* times, std::vector<double>* values);

// Throws InputError unless `times` is strictly increasing with >= 2 points;
// `source` (file or block) starts the message.
void CheckTableTimes(const std::vector<double>& times, const std::string& source);

}  // namespace mechflow::blocks
