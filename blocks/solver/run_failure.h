#pragma once
// What the simulator does when the integrator fails, and how its messages
// name the state or signal at fault.

#include <string>

#include "blocks/framework/diagram.h"
#include "blocks/solver/callback_failures.h"

namespace mechflow::blocks {

// Repeated error-test or convergence failures at one step restart the method
// from the last accepted point (order 1, a fresh history) when it took
// kRestartSteps steps since it last started and no callback failed. A
// regularised friction law's near-kinks pollute the multistep history now and
// then (stick_slip_blocks failed at t = 50.2 s, mid-stick, after 2061
// error-test failures); error control stays as it was. A dead end fails again
// sooner and ends the run.
struct RestartPolicy {
  static constexpr long kRestartSteps = 50;
  // `flag`: CVode's return; `steps_since_start`: steps since CVODE last
  // started (CVodeReInit resets the count).
  static bool Restarts(int flag, bool callback_failed, long steps_since_start);
};

// The smallest step: a few units of round-off of the run's largest time.
double MinimumStep(double t0, double t_end);

// The run's failure message for CVODE flag `flag`: its name, then why (a
// callback's reason, else CVODE's own message), a note when the step had
// fallen to the resolution of time (`step_at_resolution`; not after an
// algebraic loop without a solution, whose tiny step says nothing of the
// tolerances), and every block's own note on the failure (read from the
// run's Context `ctx`).
std::string DescribeFailure(const Diagram& diagram, Context* ctx, int flag, const CallbackFailures& failures,
                            const std::string& solver_message, bool step_at_resolution);

// "block 'b' (file:line) output 'y[1]'" for the output port that holds
// `signal` at its element, or "signal N" when no output does.
std::string DescribeSignal(const Diagram& diagram, int signal);
// "block 'b' (file:line) state 'x'" for a continuous state.
std::string DescribeState(const Diagram& diagram, int state);
// A value that is not finite as a user reads it ("nan", not "-nan").
std::string NotFiniteText(double v);

}  // namespace mechflow::blocks
