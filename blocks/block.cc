#include "blocks/block.h"

#include <algorithm>
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

void Block::DeclarePeriodicSampleTime(double period, double offset) {
  if (!(period > 0.0) || !(offset >= 0.0))
    throw std::logic_error("sample period must be > 0 and offset >= 0");
  sample_time_ = {period, offset};
}

}  // namespace mechflow::blocks
