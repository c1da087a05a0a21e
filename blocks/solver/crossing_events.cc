#include "blocks/solver/crossing_events.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "blocks/framework/evaluation.h"
#include "blocks/solver/cvode_run.h"
#include "blocks/solver/evaluate_at.h"
#include "mech/errors.h"

namespace mechflow::blocks {

std::string EventName(const Diagram& diagram, const EventRecord& event) {
  const Block& block = diagram.block(event.block);
  const std::string name = block.CrossingName(event.crossing, event.direction);
  if (!name.empty()) return block.name() + (block.type() == "mechanism" ? "." : ": ") + name;
  return "block '" + block.name() + "' zero crossing " + std::to_string(event.crossing) +
         (event.direction > 0 ? " rising" : event.direction < 0 ? " falling" : "");
}

CrossingEvents::CrossingEvents(const Diagram& diagram, Context* ctx, SolverStats* stats)
    : diagram_(diagram), ctx_(*ctx), stats_(*stats) {
  std::vector<int> directions;
  for (const int b : diagram_.crossing_blocks()) {
    for (int i = 0; i < diagram_.layout(b).num_crossings; ++i) owner_.push_back(b);
    for (int i = 0; i < diagram_.block(b).num_zero_crossings(); ++i) {
      const CrossingDirection dir = diagram_.block(b).crossing_direction(i);
      directions.push_back(dir == CrossingDirection::kRising ? 1 : dir == CrossingDirection::kFalling ? -1 : 0);
    }
  }
  search_ = std::make_unique<CrossingSearch>(std::move(directions));
  values_.assign(diagram_.num_zero_crossings(), 0.0);
  found_.assign(diagram_.num_zero_crossings(), 0);
  Reset();
}

CrossingEvents::~CrossingEvents() = default;

void CrossingEvents::Reset() {
  events_.clear();
  refiring_.Reset(diagram_.num_zero_crossings());
  probe_pending_ = false;
}

void CrossingEvents::EvaluateAt(double t, double* x, bool row) {
  blocks::EvaluateAt(diagram_, &ctx_, t, x, !row);
  ctx_.crossings = values_.data();
  EvaluateZeroCrossings(diagram_, &ctx_);
  ++stats_.root_evals;
}

void CrossingEvents::Start(double t, double* x) {
  if (empty()) return;
  EvaluateAt(t, x, false);
  search_->Start(t, values_);
  probe_pending_ = search_->AnyInactive();
}

bool CrossingEvents::Check(const CvodeRun& cvode, double t, double* x, bool row, double* t_root, double* x_root) {
  void* mem = cvode.mem();
  // the probe and the search interpolate into their own buffer: x stays
  N_Vector search = cvode.search.get();
  double* trial = cvode.search.data();
  if (probe_pending_) {
    // CVODE's look just after the start, for functions exactly zero there:
    // a tenth of the first step on (inside it, on its interpolant)
    probe_pending_ = false;
    const double t_probe = search_->lower_time() + 0.1 * (t - search_->lower_time());
    cvode.StateAt(t_probe, search);
    EvaluateAt(t_probe, trial, false);
    search_->Probe(values_);
  }
  EvaluateAt(t, x, row);
  if (!search_->Crosses(values_)) {
    search_->Accept(t, values_);
    return false;
  }
  double tn = t, h = 0.0;
  CVodeGetCurrentTime(mem, &tn);
  CVodeGetLastStep(mem, &h);
  // CVODE's tolerance on the crossing time: a hundred units of round-off
  const double ttol = 100.0 * std::numeric_limits<double>::epsilon() * (std::abs(tn) + std::abs(h));
  *t_root = search_->Locate(t, values_, ttol, [&](double tm, std::span<double> g) {
    cvode.StateAt(tm, search);
    EvaluateAt(tm, trial, false);
    std::copy(values_.begin(), values_.end(), g.begin());
  });
  std::copy(search_->directions_found().begin(), search_->directions_found().end(), found_.begin());
  const auto n = static_cast<std::size_t>(cvode.n());
  if (*t_root == t) {
    std::copy(x, x + n, x_root);
  } else {
    cvode.StateAt(*t_root, search);
    std::copy(trial, trial + n, x_root);
  }
  return true;
}

void CrossingEvents::Handle(double t) {
  blocks::EvaluateAt(diagram_, &ctx_, t, ctx_.x);
  for (int i = 0; i < diagram_.num_zero_crossings(); ++i) {
    if (found_[i] == 0 || refiring_.Fire(i, t)) continue;
    const int b = owner_[i];
    throw SimulationError("block '" + diagram_.block(b).name() + "' crossing " +
                          std::to_string(i - diagram_.layout(b).first_crossing) + " keeps firing at t = " +
                          std::to_string(t) + " (" + std::to_string(RefiringLimit::kMaxEventsPerInstant) +
                          " times at one instant: does its event handler leave it where it fires again?)");
  }
  for (int i = 0; i < diagram_.num_zero_crossings(); ++i) {
    if (found_[i] == 0) continue;
    const int b = owner_[i];
    const int local = i - diagram_.layout(b).first_crossing;
    diagram_.block(b).OnZeroCrossing(local, found_[i], BlockContext(&ctx_, &diagram_.layout(b)));
    events_.push_back({t, b, local, found_[i]});
    ++stats_.events;
  }
}

}  // namespace mechflow::blocks
