#include "blocks/solver/report_watch.h"

#include <cmath>
#include <string>

#include "mech/errors.h"

namespace mechflow::blocks {

void ReportWatch::Set(std::vector<ReportRequest> reports) {
  for (const ReportRequest& r : reports)
    if (r.index < 0 || r.index >= r.signal.width)
      throw InputError("report '" + r.label + "': signal '" + r.signal.name + "' has width " +
                       std::to_string(r.signal.width) + "; element " + std::to_string(r.index) + " does not exist");
  reports_ = std::move(reports);
  trackers_.assign(reports_.size(), ExtremumTracker());
  accumulators_.clear();
  for (const ReportRequest& r : reports_) accumulators_.emplace_back(r.level);
}

void ReportWatch::Reset(double t0) {
  for (auto& tracker : trackers_) tracker.Reset();
  for (auto& accumulator : accumulators_) accumulator.Reset();
  watched_to_ = t0;
}

void ReportWatch::WatchStep(double ta, double tb, const std::function<void(double)>& evaluate_at) {
  for (std::size_t i = 0; i < reports_.size(); ++i) {
    const ReportRequest& r = reports_[i];
    const int offset = r.signal.offset + r.index;
    const auto value = [&](double t) {
      evaluate_at(t);
      return signals_[offset];
    };
    if (!IsExtremum(r.kind)) {
      accumulators_[i].WatchStep(ta, tb, value);
      continue;
    }
    const double sign = r.kind == ReportKind::kMin ? -1.0 : 1.0;
    const bool magnitude = r.kind == ReportKind::kPeakAbs;
    trackers_[i].WatchStep(ta, tb, [&](double t) {
      const double v = value(t);
      return magnitude ? std::abs(v) : sign * v;
    });
  }
}

std::vector<ReportFigure> ReportWatch::figures() const {
  std::vector<ReportFigure> out;
  for (std::size_t i = 0; i < reports_.size(); ++i) {
    const ReportRequest& r = reports_[i];
    ReportFigure f{r.label, r.unit, r.signal.name, r.kind, trackers_[i].found()};
    const SignalAccumulator& a = accumulators_[i];
    if (IsExtremum(r.kind) && f.found) {
      // the tracker maximised -f for a minimum
      f.value = r.kind == ReportKind::kMin ? -trackers_[i].value() : trackers_[i].value();
      f.time = trackers_[i].time();
    } else if (!IsExtremum(r.kind)) {
      f.found = r.kind == ReportKind::kCrossing ? a.crossed()
                : r.kind == ReportKind::kPeriod ? a.has_period()
                                                : a.started();
      if (f.found) {
        switch (r.kind) {
          case ReportKind::kMean: f.value = a.mean(), f.time = a.end(); break;
          case ReportKind::kRms: f.value = a.rms(), f.time = a.end(); break;
          case ReportKind::kIntegral: f.value = a.integral(), f.time = a.end(); break;
          case ReportKind::kFinal: f.value = a.final_value(), f.time = a.end(); break;
          case ReportKind::kCrossing: f.value = f.time = a.first_crossing(); break;
          case ReportKind::kPeriod: f.value = a.period(), f.time = a.last_upward(); break;
          default: break;
        }
      }
    }
    f.value *= r.signal.column_factor;  // in the report's unit (SignalRef::column_factor)
    out.push_back(std::move(f));
  }
  return out;
}

}  // namespace mechflow::blocks
