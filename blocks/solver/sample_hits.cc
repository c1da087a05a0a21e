#include "blocks/solver/sample_hits.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "blocks/solver/evaluate_at.h"
#include "blocks/solver/grid_time.h"

namespace mechflow::blocks {

SampleHits::SampleHits(const Diagram& diagram, Context* ctx, SolverStats* stats)
    : diagram_(diagram), ctx_(*ctx), stats_(*stats), next_hit_(diagram.periodic_blocks().size(), 0) {}

void SampleHits::Reset(double t0) {
  const auto& periodic = diagram_.periodic_blocks();
  for (size_t i = 0; i < periodic.size(); ++i) {
    const SampleTime& st = diagram_.block(periodic[i]).sample_time();
    next_hit_[i] = static_cast<long>(std::max(0.0, std::ceil((t0 - st.offset) / st.period)));
  }
}

double SampleHits::Next() const {
  double next = std::numeric_limits<double>::infinity();
  const auto& periodic = diagram_.periodic_blocks();
  for (size_t i = 0; i < periodic.size(); ++i) {
    const SampleTime& st = diagram_.block(periodic[i]).sample_time();
    next = std::min(next, DecimalGridTime(st.offset + next_hit_[i] * st.period));  // as the rows' times
  }
  return next;
}

void SampleHits::Handle(double t) {
  const auto& periodic = diagram_.periodic_blocks();
  EvaluateAt(diagram_, &ctx_, t, ctx_.x);
  for (size_t i = 0; i < periodic.size(); ++i) {
    const SampleTime& st = diagram_.block(periodic[i]).sample_time();
    // the same formula that produced the stop time, so equality is exact --
    // except at t_end, which a hit may pass by a rounding (3 * 0.1 > 0.3)
    if (!SameInstant(DecimalGridTime(st.offset + next_hit_[i] * st.period), t)) continue;
    diagram_.block(periodic[i]).OnSampleHit(BlockContext(&ctx_, &diagram_.layout(periodic[i])));
    ++next_hit_[i];
    ++stats_.sample_hits;
  }
}

}  // namespace mechflow::blocks
