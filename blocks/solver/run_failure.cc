#include "blocks/solver/run_failure.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <cvode/cvode.h>

#include "blocks/solver/sundials.h"

namespace mechflow::blocks {

bool RestartPolicy::Restarts(int flag, bool callback_failed, long steps_since_start) {
  return (flag == CV_ERR_FAILURE || flag == CV_CONV_FAILURE) && !callback_failed &&
         steps_since_start >= kRestartSteps;
}

double MinimumStep(double t0, double t_end) {
  return 8.0 * std::numeric_limits<double>::epsilon() * std::max({std::abs(t0), std::abs(t_end), 1e-300});
}

std::string DescribeFailure(const Diagram& diagram, Context* ctx, int flag, const CallbackFailures& failures,
                            const std::string& solver_message, bool step_at_resolution) {
  std::string failure = sundials::CvodeFlagName(flag);
  if (failures.any()) failure += ": " + failures.reason();
  else if (!solver_message.empty()) failure += ": " + solver_message;
  if (!(failures.no_solution() && failures.any()) && step_at_resolution)
    failure += " (the step size fell to the resolution of time: the solver cannot meet the tolerances "
               "here; a singular position, a discontinuity without an event, or rtol below what the "
               "model's round-off allows)";
  for (int b = 0; b < diagram.num_blocks(); ++b) {
    const std::string note = diagram.block(b).FailureNote(BlockContext(ctx, &diagram.layout(b)));
    if (!note.empty()) failure += "; block '" + diagram.block(b).name() + "': " + note;
  }
  return failure;
}

std::string DescribeSignal(const Diagram& diagram, int signal) {
  for (int b = 0; b < diagram.num_blocks(); ++b) {
    const BlockLayout& layout = diagram.layout(b);
    for (int p = 0; p < static_cast<int>(layout.output_offset.size()); ++p) {
      const int first = layout.output_offset[p], width = layout.output_width[p];
      if (signal < first || signal >= first + width) continue;
      const std::string& origin = diagram.origin(b);
      std::string port = diagram.block(b).output_port(p).name;
      if (width > 1) port += "[" + std::to_string(signal - first) + "]";
      return "block '" + diagram.block(b).name() + "'" + (origin.empty() ? "" : " (" + origin + ")") + " output '" +
             port + "'";
    }
  }
  return "signal " + std::to_string(signal);
}

std::string DescribeState(const Diagram& diagram, int state) {
  for (const int b : diagram.stateful_blocks()) {
    const BlockLayout& layout = diagram.layout(b);
    if (state < layout.first_state || state >= layout.first_state + layout.num_states) continue;
    const std::string& origin = diagram.origin(b);
    return "block '" + diagram.block(b).name() + "'" + (origin.empty() ? "" : " (" + origin + ")") + " state '" +
           diagram.block(b).state_name(state - layout.first_state) + "'";
  }
  return "continuous state " + std::to_string(state);
}

std::string NotFiniteText(double v) { return std::isnan(v) ? "nan" : v > 0 ? "inf" : "-inf"; }

}  // namespace mechflow::blocks
