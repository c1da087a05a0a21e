#include "blocks/library/sources.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>

#include "mech/errors.h"

namespace mechflow::blocks {

ConstantBlock::ConstantBlock(const std::string& name, std::vector<double> value)
    : Block("constant", name), value_(std::move(value)) {
  DeclareOutputPort("y", static_cast<int>(value_.size()));
}

void ConstantBlock::DoCalcOutput(int, const BlockContext& ctx) const {
  std::copy(value_.begin(), value_.end(), ctx.output(0).begin());
}

ClockBlock::ClockBlock(const std::string& name) : Block("clock", name) { DeclareOutputPort("y"); }

void ClockBlock::DoCalcOutput(int, const BlockContext& ctx) const { ctx.output(0)[0] = ctx.time(); }

SwitchAtTimeBlock::SwitchAtTimeBlock(const std::string& type, const std::string& name, double switch_time)
    : Block(type, name), switch_time_(switch_time) {
  DeclareOutputPort("y");
  DeclareDiscreteStates(1);
  DeclareZeroCrossing(CrossingDirection::kRising);
}

void SwitchAtTimeBlock::DoInitialize(const BlockContext& ctx) const {
  ctx.discrete()[0] = ctx.time() >= switch_time_ ? 1.0 : 0.0;
}

void SwitchAtTimeBlock::DoCalcZeroCrossings(const BlockContext& ctx) const {
  ctx.zero_crossings()[0] = ctx.time() - switch_time_;
}

void SwitchAtTimeBlock::DoZeroCrossing(int, int, const BlockContext& ctx) const { ctx.discrete()[0] = 1.0; }

bool SwitchAtTimeBlock::DoUpdateModes(const BlockContext& ctx) const {
  const double mode = ctx.time() >= switch_time_ ? 1.0 : 0.0;
  const bool changed = mode != ctx.discrete()[0];
  ctx.discrete()[0] = mode;
  return changed;
}

StepBlock::StepBlock(const std::string& name, double time, double before, double after)
    : SwitchAtTimeBlock("step", name, time), before_(before), after_(after) {}

void StepBlock::DoCalcOutput(int, const BlockContext& ctx) const {
  ctx.output(0)[0] = switched(ctx) ? after_ : before_;
}

RampBlock::RampBlock(const std::string& name, double slope, double start, double initial)
    : SwitchAtTimeBlock("ramp", name, start), slope_(slope), initial_(initial) {}

void RampBlock::DoCalcOutput(int, const BlockContext& ctx) const {
  ctx.output(0)[0] = initial_ + (switched(ctx) ? slope_ * (ctx.time() - switch_time()) : 0.0);
}

SineBlock::SineBlock(const std::string& name, double amplitude, double frequency, double phase, double bias)
    : Block("sine", name), amplitude_(amplitude), omega_(2.0 * M_PI * frequency), phase_(phase), bias_(bias) {
  DeclareOutputPort("y");
}

void SineBlock::DoCalcOutput(int, const BlockContext& ctx) const {
  ctx.output(0)[0] = bias_ + amplitude_ * std::sin(omega_ * ctx.time() + phase_);
}

TableBlock::TableBlock(const std::string& name, std::vector<double> times, std::vector<double> values)
    : Block("table", name), times_(std::move(times)), values_(std::move(values)) {
  DeclareOutputPort("y");
}

void TableBlock::DoCalcOutput(int, const BlockContext& ctx) const {
  const double t = ctx.time();
  double& y = ctx.output(0)[0];
  if (t <= times_.front()) {
    y = values_.front();
  } else if (t >= times_.back()) {
    y = values_.back();
  } else {
    const size_t i = std::upper_bound(times_.begin(), times_.end(), t) - times_.begin();  // times_[i-1] <= t < times_[i]
    const double s = (t - times_[i - 1]) / (times_[i] - times_[i - 1]);
    y = values_[i - 1] + s * (values_[i] - values_[i - 1]);
  }
}

void CheckTableTimes(const std::vector<double>& times, const std::string& source) {
  if (times.size() < 2) throw InputError(source + ": a table needs at least two points");
  for (size_t i = 1; i < times.size(); ++i)
    if (!(times[i] > times[i - 1]))
      throw InputError(source + ": times must increase strictly, but point " + std::to_string(i + 1) + " (t = " +
                       std::to_string(times[i]) + ") does not come after point " + std::to_string(i) + " (t = " +
                       std::to_string(times[i - 1]) + ")");
}

void ReadTableCsv(const std::string& path, std::vector<double>* times, std::vector<double>* values) {
  std::ifstream in(path);
  if (!in) throw InputError("cannot open table file '" + path + "'");
  std::string line;
  int line_number = 0;
  bool seen_numbers = false;
  while (std::getline(in, line)) {
    ++line_number;
    const auto hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    for (char& c : line)
      if (c == ',' || c == ';' || c == '\t' || c == '\r') c = ' ';
    std::vector<double> row;
    size_t pos = 0;
    bool numeric = true;
    while (true) {
      pos = line.find_first_not_of(' ', pos);
      if (pos == std::string::npos) break;
      const size_t end = std::min(line.find(' ', pos), line.size());
      double v = 0;
      const auto [ptr, error] = std::from_chars(line.data() + pos, line.data() + end, v);
      if (error != std::errc() || ptr != line.data() + end) numeric = false;
      row.push_back(v);
      pos = end;
    }
    if (row.empty()) continue;
    const std::string where = path + ":" + std::to_string(line_number);
    if (!numeric) {
      if (!seen_numbers && times->empty()) {
        seen_numbers = true;  // the one header line allowed
        continue;
      }
      throw InputError(where + ": expected two numbers (t, y), found '" + line + "'");
    }
    seen_numbers = true;
    if (row.size() != 2)
      throw InputError(where + ": expected two numbers (t, y), found " + std::to_string(row.size()));
    if (!times->empty() && !(row[0] > times->back()))
      throw InputError(where + ": times must increase strictly (t = " + std::to_string(row[0]) +
                       " after t = " + std::to_string(times->back()) + ")");
    times->push_back(row[0]);
    values->push_back(row[1]);
  }
  CheckTableTimes(*times, path);
}

}  // namespace mechflow::blocks
