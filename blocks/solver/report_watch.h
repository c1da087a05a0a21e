#pragma once
// ReportWatch: the figures a diagram asks for (blocks/outputs/report.h), located
// while the run goes: each report sees the solution on every stretch the
// integrator has passed, evaluated on the step's interpolant.

#include <cmath>
#include <functional>
#include <vector>

#include "blocks/outputs/report.h"

namespace mechflow::blocks {

class ReportWatch {
 public:
  // `signals`: where each report's signal is read after an evaluation (the
  // Context's; not owned).
  explicit ReportWatch(const std::vector<double>& signals) : signals_(signals) {}

  // Throws InputError when a report's element is outside its signal's width.
  void Set(std::vector<ReportRequest> reports);
  bool empty() const { return reports_.empty(); }

  // A new run from t0: nothing watched yet.
  void Reset(double t0);
  // What the solver found beyond t (a watched stretch) is void: watching
  // goes on from t.
  void Restart(double t) { watched_to_ = t; }
  // Lets the reports see the solution on (watched_to_, t], within the last
  // step; `evaluate_at(t)` brings every signal up to date at t inside it.
  // A step longer than the longest piece (SetLongestPiece) is watched in
  // equal pieces no longer than that.
  template <class EvaluateAt>
  void WatchTo(double t, EvaluateAt&& evaluate_at) {
    if (reports_.empty() || !(t > watched_to_)) return;
    const std::function<void(double)> at(evaluate_at);
    // equal pieces: each time the rest of the step over the pieces left
    for (double left = std::ceil((t - watched_to_) / longest_piece_); left > 1; --left) {
      const double tk = watched_to_ + (t - watched_to_) / left;
      WatchStep(watched_to_, tk, at);
      watched_to_ = tk;
    }
    WatchStep(watched_to_, t, at);
    watched_to_ = t;
  }
  // The longest stretch watched at once (a fraction of the fastest source's
  // period, Block::OwnTimeScale); infinity: a step at a time.
  void SetLongestPiece(double longest) { longest_piece_ = longest; }

  // The figures so far, in the reports' units.
  std::vector<ReportFigure> figures() const;

 private:
  void WatchStep(double ta, double tb, const std::function<void(double)>& evaluate_at);

  const std::vector<double>& signals_;
  std::vector<ReportRequest> reports_;
  std::vector<ExtremumTracker> trackers_;       // one per report (its extremum kinds)
  std::vector<SignalAccumulator> accumulators_;  // one per report (the other kinds)
  double watched_to_ = 0.0;  // reports have watched the solution up to here
  double longest_piece_ = INFINITY;
};

}  // namespace mechflow::blocks
