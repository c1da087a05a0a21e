#include "blocks/solver/solver_options.h"

#include <cmath>

namespace mechflow::blocks {

std::string SolverOptions::Problem() const {
  if (!std::isfinite(t_start)) return "t_start must be a finite number";
  if (!(t_end > t_start) || !std::isfinite(t_end))
    return "t_end must be a finite number greater than t_start (" + std::to_string(t_start) + ")";
  if (!(rtol >= 1e-15) || !(rtol < 1.0))
    return "rtol must be at least 1e-15 (double precision cannot follow a tighter one) and < 1";
  if (!(atol > 0.0) || !std::isfinite(atol)) return "atol must be a finite number > 0";
  if (!(max_step >= 0.0) || !std::isfinite(max_step)) return "max_step must be >= 0 (0 means no limit)";
  if (!(initial_step >= 0.0) || !std::isfinite(initial_step))
    return "initial_step must be >= 0 (0 means automatic)";
  if (max_steps < 1) return "max_steps must be >= 1";
  if (!(output_interval >= 0.0) || !std::isfinite(output_interval)) return "output interval must be >= 0";
  return "";
}

}  // namespace mechflow::blocks
