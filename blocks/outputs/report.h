#pragma once
// Reports: figures a diagram asks for (<report>, diagrams/FORMAT.md
// "Reports"), e.g. the peak contact force and when it happens, located by the
// integrator rather than read off the output grid.
//
// Method (ExtremumTracker): the simulator shows the tracker every internal
// CVODE step [ta, tb] together with the signal evaluated on that step's own
// interpolating polynomial (CVodeGetDky, then the diagram's outputs):
//   f(ta), f(ta + e), f(tb - e), f(tb)     e = 1e-3 (tb - ta)
//   the ends are candidates;
//   if f rises after ta and falls before tb, the step holds an interior
//     maximum: golden-section search on [ta, tb] finds it
// so a figure is as accurate as the solution (the solver's tolerances),
// whatever the output interval. Cost: 4 output evaluations per step, about
// 50 more per local maximum. A root function on the signal's derivative was
// not chosen: the block interface has no signal derivatives, and every root
// would stop and restart CVODE at each local maximum of the signal.
// A minimum is the maximum of -f, the largest magnitude that of |f|.
//
// The other figures (extremes, crossings, settling) watch the same steps
// (SignalAccumulator): the integral by 3-point Gauss-Legendre on each step's
// polynomial (exact for CVODE's interpolants up to degree 5), the mean and
// rms from it over the time watched, the final value at the last step's
// end, and the crossings of a level: a sign change of f - level over a step
// is located by bisection on the polynomial to 1e-12 of the step; the first
// is the crossing figure, and the mean spacing of the upward ones (at least
// two) the period.

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "blocks/framework/diagram.h"

namespace mechflow::blocks {

enum class ReportKind {
  kPeak,      // largest value
  kMin,       // smallest value
  kPeakAbs,   // largest |value| (the figure is the magnitude)
  kMean,      // mean over the run (integral / duration)
  kRms,       // root mean square over the run
  kIntegral,  // integral over the run [signal s]
  kFinal,     // the value at the end
  kCrossing,  // the time the signal first reaches `level` (either way) [s]
  kPeriod,    // mean time between upward crossings of `level` [s]
};
inline constexpr ReportKind kReportKinds[] = {ReportKind::kPeak,     ReportKind::kMin,   ReportKind::kPeakAbs,
                                              ReportKind::kMean,     ReportKind::kRms,   ReportKind::kIntegral,
                                              ReportKind::kFinal,    ReportKind::kCrossing, ReportKind::kPeriod};

// The <report> attribute of each kind.
inline const char* ReportKindName(ReportKind kind) {
  switch (kind) {
    case ReportKind::kPeak: return "peak";
    case ReportKind::kMin: return "min";
    case ReportKind::kPeakAbs: return "peak_abs";
    case ReportKind::kMean: return "mean";
    case ReportKind::kRms: return "rms";
    case ReportKind::kIntegral: return "integral";
    case ReportKind::kFinal: return "final";
    case ReportKind::kCrossing: return "crossing";
    case ReportKind::kPeriod: return "period";
  }
  return "";
}
inline bool IsExtremum(ReportKind kind) {
  return kind == ReportKind::kPeak || kind == ReportKind::kMin || kind == ReportKind::kPeakAbs;
}

// One figure asked for; the signal is resolved once, before the run.
struct ReportRequest {
  std::string label;   // e.g. "peak contact force"
  std::string unit;    // printed after the value; may be empty
  ReportKind kind = ReportKind::kPeak;
  SignalRef signal;    // as logged; name = "block.port"
  int index = 0;       // element of a vector signal
  double level = 0.0;  // crossing, period
};

// A figure found by a run (also by a failed run: up to its failure).
struct ReportFigure {
  std::string label, unit, signal;
  ReportKind kind = ReportKind::kPeak;
  bool found = false;  // false when the run took no step
  double value = std::numeric_limits<double>::quiet_NaN();  // signal units
  double time = std::numeric_limits<double>::quiet_NaN();   // [s]
};

// The running maximum of f(t) over the steps shown to it.
class ExtremumTracker {
 public:
  void Reset() { found_ = false; }
  bool found() const { return found_; }
  double value() const { return value_; }  // of f
  double time() const { return time_; }

  // One accepted step [ta, tb] (ta < tb); f(t) is valid on the whole step.
  template <class F>
  void WatchStep(double ta, double tb, F&& f) {
    const double e = 1e-3 * (tb - ta);
    const double fa = f(ta), fa2 = f(ta + e), fb2 = f(tb - e), fb = f(tb);
    Offer(ta, fa);
    Offer(tb, fb);
    if (!(fa2 > fa && fb2 > fb)) return;
    // golden-section search on a unimodal bracket; stops when the bracket is
    // below 1e-9 of the step or a few ulps of t (a flat top resolves t only
    // to about sqrt(machine epsilon) of the step anyway)
    constexpr double kInvPhi = 0.6180339887498949;
    double a = ta, b = tb;
    double c = b - kInvPhi * (b - a), d = a + kInvPhi * (b - a);
    double fc = f(c), fd = f(d);
    const double tol = std::max(1e-9 * (tb - ta), 8 * std::numeric_limits<double>::epsilon() * std::abs(tb));
    for (int i = 0; i < 80 && b - a > tol; ++i) {
      if (fc >= fd) {
        b = d, d = c, fd = fc;
        c = b - kInvPhi * (b - a);
        fc = f(c);
      } else {
        a = c, c = d, fc = fd;
        d = a + kInvPhi * (b - a);
        fd = f(d);
      }
    }
    if (fc >= fd) Offer(c, fc);
    else Offer(d, fd);
  }

 private:
  void Offer(double t, double v) {
    if (!std::isfinite(v) || (found_ && v <= value_)) return;
    found_ = true;
    value_ = v;
    time_ = t;
  }

  bool found_ = false;
  double value_ = 0.0, time_ = 0.0;
};

// Integral, mean, rms, final value and crossings of f(t) over the steps
// shown to it (see the top of this file).
class SignalAccumulator {
 public:
  explicit SignalAccumulator(double level = 0.0) : level_(level) {}
  void Reset() { *this = SignalAccumulator(level_); }

  template <class F>
  void WatchStep(double ta, double tb, F&& f) {
    // Gauss-Legendre, 3 points
    constexpr double kNode = 0.7745966692414834, kOuter = 5.0 / 9.0, kMiddle = 8.0 / 9.0;
    const double mid = 0.5 * (ta + tb), half = 0.5 * (tb - ta);
    const double f1 = f(mid - kNode * half), f2 = f(mid), f3 = f(mid + kNode * half);
    integral_ += half * (kOuter * (f1 + f3) + kMiddle * f2);
    square_ += half * (kOuter * (f1 * f1 + f3 * f3) + kMiddle * f2 * f2);
    const double fa = f(ta), fb = f(tb);
    if (!started_) start_ = ta, started_ = true;
    end_ = tb;
    final_ = fb;
    const double ga = fa - level_, gb = fb - level_;
    if (ga == 0.0 || !(ga * gb < 0.0)) {
      if (ga == 0.0 && (!first_found_)) first_found_ = true, first_ = ta;
      return;
    }
    double a = ta, b = tb, g_a = ga;
    for (int i = 0; i < 200 && b - a > 1e-12 * (tb - ta); ++i) {
      const double c = 0.5 * (a + b), gc = f(c) - level_;
      if ((gc < 0.0) == (g_a < 0.0)) a = c, g_a = gc;
      else b = c;
    }
    const double t = 0.5 * (a + b);
    if (!first_found_) first_found_ = true, first_ = t;
    if (ga < 0.0) {  // upward
      if (upward_ == 0) first_up_ = t;
      last_up_ = t;
      ++upward_;
    }
  }

  bool started() const { return started_; }
  double duration() const { return end_ - start_; }
  double end() const { return end_; }
  double integral() const { return integral_; }
  double mean() const { return duration() > 0.0 ? integral_ / duration() : final_; }
  double rms() const { return duration() > 0.0 ? std::sqrt(square_ / duration()) : std::abs(final_); }
  double final_value() const { return final_; }
  bool crossed() const { return first_found_; }
  double first_crossing() const { return first_; }
  bool has_period() const { return upward_ >= 2; }
  double period() const { return (last_up_ - first_up_) / (upward_ - 1); }
  double last_upward() const { return last_up_; }

 private:
  double level_ = 0.0;
  bool started_ = false, first_found_ = false;
  double start_ = 0.0, end_ = 0.0, integral_ = 0.0, square_ = 0.0, final_ = 0.0;
  double first_ = 0.0, first_up_ = 0.0, last_up_ = 0.0;
  int upward_ = 0;
};

}  // namespace mechflow::blocks
