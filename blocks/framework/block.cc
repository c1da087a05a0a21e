#include "blocks/framework/block.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace mechflow::blocks {

Block::Block(std::string type, std::string name) : type_(std::move(type)), name_(std::move(name)) {}

int Block::FindInput(std::string_view port_name) const {
  for (int i = 0; i < num_inputs(); ++i)
    if (inputs_[i].name == port_name) return i;
  return -1;
}

int Block::FindOutput(std::string_view port_name) const {
  for (int i = 0; i < num_outputs(); ++i)
    if (outputs_[i].name == port_name) return i;
  return -1;
}

bool Block::HasFeedthrough(int in, int out) const {
  if (no_feedthrough_at_all_) return false;
  return std::find(no_feedthrough_.begin(), no_feedthrough_.end(), std::make_pair(in, out)) ==
         no_feedthrough_.end();
}

int Block::DeclareInputPort(std::string port_name, int width) {
  if (width < 1) throw std::logic_error("port width must be >= 1");
  inputs_.push_back({std::move(port_name), width});
  return num_inputs() - 1;
}

int Block::DeclareOutputPort(std::string port_name, int width) {
  if (width < 1) throw std::logic_error("port width must be >= 1");
  outputs_.push_back({std::move(port_name), width});
  return num_outputs() - 1;
}

void Block::SetFeedthrough(int in, int out, bool direct) {
  const auto pair = std::make_pair(in, out);
  const auto it = std::find(no_feedthrough_.begin(), no_feedthrough_.end(), pair);
  if (direct && it != no_feedthrough_.end()) no_feedthrough_.erase(it);
  if (!direct && it == no_feedthrough_.end()) no_feedthrough_.push_back(pair);
}

void Block::DeclareNoFeedthrough() { no_feedthrough_at_all_ = true; }

void Block::DeclareContinuousStates(int n, const std::string& prefix) {
  for (int i = 0; i < n; ++i)
    state_names_.push_back(n == 1 ? prefix : prefix + "[" + std::to_string(i) + "]");
}

int Block::DeclareZeroCrossing(CrossingDirection direction) {
  crossings_.push_back(direction);
  return num_zero_crossings() - 1;
}

std::string SamplePeriodProblem(double period, double t_start, double t_end) {
  if (!(period > 0.0) || !std::isfinite(period)) return "the period must be a finite number > 0 (s)";
  const double span = t_end - t_start;
  const double resolution = 1e-12 * std::max(std::abs(t_start), std::abs(t_end));
  const double least = std::max(span / kMaxSampleHits, resolution);
  if (period >= least) return "";
  char text[256];
  std::snprintf(text, sizeof text,
                "the period %.6g s is too small for the run from t = %.6g to %.6g s (%s); use at least %.6g s", period,
                t_start, t_end,
                resolution > span / kMaxSampleHits ? "times that close cannot be told apart in double precision"
                                                    : "more than 1e8 instants in the run",
                least);
  return text;
}

void Block::DeclarePeriodicSampleTime(double period, double offset) {
  if (!(period > 0.0) || !(offset >= 0.0))
    throw std::logic_error("sample period must be > 0 and offset >= 0");
  sample_time_ = {period, offset};
}

void Block::DeclareRatePair(int position, int rate) {
  const int n = num_states();
  if (position < 0 || position >= n || rate < 0 || rate >= n || position == rate)
    throw std::logic_error("block '" + name_ + "': rate pair (" + std::to_string(position) + ", " +
                           std::to_string(rate) + ") is not two of its states");
  for (const auto& [p, r] : rate_pairs_)
    if (p == position || p == rate || r == position)
      throw std::logic_error("block '" + name_ + "': state " + std::to_string(position) +
                             " is in two rate pairs, or a position is another pair's rate");
  rate_pairs_.emplace_back(position, rate);
}

void Block::DeclareSparsity(BlockSparsity sparsity) {
  const auto in_range = [](const std::vector<std::vector<int>>& lists, int limit) {
    for (const auto& list : lists)
      for (const int i : list)
        if (i < 0 || i >= limit) return false;
    return true;
  };
  if (static_cast<int>(sparsity.derivative_states.size()) != num_states() ||
      static_cast<int>(sparsity.derivative_inputs.size()) != num_states() ||
      static_cast<int>(sparsity.output_states.size()) != num_outputs() ||
      !in_range(sparsity.derivative_states, num_states()) || !in_range(sparsity.derivative_inputs, num_inputs()) ||
      !in_range(sparsity.output_states, num_states()))
    throw std::logic_error("block '" + name_ + "': sparsity does not match its states and ports");
  if (num_states() == 0) return;  // nothing to say: the default covers outputs of stateless blocks
  sparsity_ = std::move(sparsity);
}

}  // namespace mechflow::blocks
