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

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "blocks/diagram.h"

namespace mechflow::blocks {

enum class ReportKind {
  kPeak,     // largest value
  kMin,      // smallest value
  kPeakAbs,  // largest |value| (the figure is the magnitude)
};

// "peak", "min", "peak_abs": the <report> attribute of each kind.
inline const char* ReportKindName(ReportKind kind) {
  return kind == ReportKind::kPeak ? "peak" : kind == ReportKind::kMin ? "min" : "peak_abs";
}

// One figure asked for; the signal is resolved once, before the run.
struct ReportRequest {
  std::string label;   // e.g. "peak contact force"
  std::string unit;    // printed after the value; may be empty
  ReportKind kind = ReportKind::kPeak;
  SignalRef signal;    // as logged; name = "block.port"
  int index = 0;       // element of a vector signal
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

}  // namespace mechflow::blocks
