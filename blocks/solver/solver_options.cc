#include "blocks/solver/solver_options.h"

#include <cmath>

#include "blocks/outputs/csv.h"

namespace mechflow::blocks {

std::string SolverOptions::Problem() const {
  if (!std::isfinite(t_start)) return "t_start must be a finite number";
  if (!(t_end > t_start) || !std::isfinite(t_end))
    return "t_end = " + CsvNumber(t_end) + " s: it must be a finite number greater than t_start = " +
           CsvNumber(t_start) + " s";
  if (!(rtol >= 1e-15) || !(rtol < 1.0))
    return "rtol = " + CsvNumber(rtol) + ": it must be at least 1e-15 (double precision cannot follow a tighter one) and < 1";
  if (!(atol > 0.0) || !std::isfinite(atol)) return "atol = " + CsvNumber(atol) + ": it must be a finite number > 0";
  if (!(max_step >= 0.0) || !std::isfinite(max_step)) return "max_step must be >= 0 (0 means no limit)";
  if (!(initial_step >= 0.0) || !std::isfinite(initial_step))
    return "initial_step must be >= 0 (0 means automatic)";
  if (max_steps < 1) return "max_steps must be >= 1";
  if (!(output_interval >= 0.0) || !std::isfinite(output_interval)) return "output interval must be >= 0";
  return OutputTimesProblem();
}

std::string SolverOptions::OutputTimesProblem() const {
  const auto at = [](std::size_t i, double t) {
    return "the output time " + CsvNumber(t) + " s (number " + std::to_string(i + 1) + " in the list)";
  };
  for (std::size_t i = 0; i < output_times.size(); ++i) {
    const double t = output_times[i];
    if (!std::isfinite(t)) return at(i, t) + " is not a finite number";
    if (t < t_start) return at(i, t) + " is before t_start = " + CsvNumber(t_start) + " s";
    if (t > t_end)
      return at(i, t) + " is after t_end = " + CsvNumber(t_end) + " s: run to t_end = " + CsvNumber(output_times.back()) +
             " s at least";
    if (i > 0 && !(t > output_times[i - 1]))
      return at(i, t) + " is not after the one before (" + CsvNumber(output_times[i - 1]) +
             " s): the times must increase";
  }
  return "";
}

}  // namespace mechflow::blocks
