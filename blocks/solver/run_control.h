#pragma once
// RunControl: code that acts on a run between integrator steps -- a control
// script (scripting/control_script.h) replacing the old compiled control files.
//
// The simulator calls it at four kinds of instant, always with the outputs
// evaluated at the current time and state:
//   Start   once, at t_start, before the first row is recorded;
//   Timer   at the times NextTimer() names; the integrator stops exactly
//           there, as it does for periodic blocks (after their sample hits);
//   Output  at every output time after t_start, before its row is recorded,
//           so the row shows what the control did at that instant;
//   Finish  once, after the last row of a run that did not fail.
// Through ControlPoint it reads signals and may change discrete states (an
// identifier block's value) or stop the run. After a call that changed
// something, the simulator settles the modes and re-initialises the
// integrator, as after an event. A control reports an error by throwing
// SimulationError: the run ends there with the results so far.

#include <limits>
#include <span>
#include <string>

namespace mechflow::blocks {

class ControlPoint {
 public:
  virtual ~ControlPoint() = default;
  virtual double time() const = 0;
  // The time the run ends at (its t_end).
  virtual double end_time() const = 0;
  // Every output port's current value, packed (Diagram::ResolveSignal gives offsets).
  virtual std::span<const double> signals() const = 0;
  // Discrete states, for changes; call Changed() after writing them.
  virtual std::span<double> discrete() = 0;
  // Something the outputs depend on changed (discrete states, parameters):
  // the outputs are evaluated again at once, so later reads see the change,
  // and the integrator is re-initialised after the call.
  virtual void Changed() = 0;
  // Ends the run after this call, successfully, with `reason` reported.
  virtual void Stop(std::string reason) = 0;
};

class RunControl {
 public:
  virtual ~RunControl() = default;
  virtual void Start(ControlPoint& point) = 0;
  virtual void Output(ControlPoint& point) = 0;
  // The next time Timer must run at, +infinity for none; read after every
  // call, so a control may add timers as it goes.
  virtual double NextTimer() const { return std::numeric_limits<double>::infinity(); }
  // Runs every timer due at point.time() (== the last NextTimer()).
  virtual void Timer(ControlPoint&) {}
  virtual void Finish(ControlPoint& point) = 0;
};

}  // namespace mechflow::blocks
