#include "blocks/library/sample_hold.h"

#include <algorithm>

namespace mechflow::blocks {

SampleHoldBlock::SampleHoldBlock(const std::string& name, double period, double offset, std::vector<double> initial)
    : Block("sample_hold", name), initial_(std::move(initial)) {
  const int w = static_cast<int>(initial_.size());
  DeclareInputPort("u", w);
  DeclareOutputPort("y", w);
  DeclareNoFeedthrough();
  DeclareDiscreteStates(w);
  DeclarePeriodicSampleTime(period, offset);
}

void SampleHoldBlock::DoInitialize(const BlockContext& ctx) const {
  std::copy(initial_.begin(), initial_.end(), ctx.discrete().begin());
}

void SampleHoldBlock::DoCalcOutput(int, const BlockContext& ctx) const {
  const auto held = ctx.discrete();
  std::copy(held.begin(), held.end(), ctx.output(0).begin());
}

void SampleHoldBlock::DoSampleHit(const BlockContext& ctx) const {
  const auto u = ctx.input(0);
  std::copy(u.begin(), u.end(), ctx.discrete().begin());
}

}  // namespace mechflow::blocks
