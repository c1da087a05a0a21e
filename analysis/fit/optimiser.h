#pragma once
// The optimisers of a fit, both in the unit box [0, 1]^n of the parameters
// (analysis/fit/parameters.h), both minimising the sum of squared residuals:
//   LevenbergMarquardt  Ceres' trust-region Levenberg-Marquardt with bounds,
//                       the Jacobian by forward differences (Objective), its
//                       runs in parallel; for smooth costs.
//   DerivativeFree      NLopt's BOBYQA (Powell's bounded quadratic models,
//                       no derivatives; Nelder-Mead for one parameter, which
//                       BOBYQA does not take); for costs that stick/slip or
//                       contact make non-smooth, where differences mislead.

#include <csignal>
#include <string>
#include <vector>

#include "analysis/fit/objective.h"

namespace mechflow::analysis::fit {

struct OptimiserResult {
  std::vector<double> u;         // the best point found
  std::vector<double> history;   // the cost after every iteration (the start first)
  int iterations = 0;
  bool converged = false;
  bool interrupted = false;
  std::string report;            // the optimiser's own word on why it stopped
};

OptimiserResult LevenbergMarquardt(Objective& objective, const std::vector<double>& start, int max_iterations,
                                   const volatile std::sig_atomic_t* interrupt);
OptimiserResult DerivativeFree(Objective& objective, const std::vector<double>& start, int max_evaluations,
                               const volatile std::sig_atomic_t* interrupt);

}  // namespace mechflow::analysis::fit
