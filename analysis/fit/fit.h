#pragma once
// Fitting free parameters of a diagram to measured data (mechflow fit).
//
//   analysis::fit::Fitter fitter(setup);  // everything checked; no run yet
//   fitter.Probe();                       // each parameter must move a matched output
//   const FitResult r = fitter.Run({});   // optimise, then standard errors
//
// The experiments (analysis/fit/experiment.h) are fitted together with one
// set of parameter values; their residuals (analysis/fit/residuals.h) are
// minimised in the least-squares sense by Levenberg-Marquardt or a
// derivative-free method (analysis/fit/optimiser.h), and the Jacobian at the
// solution gives standard errors and correlations (analysis/fit/statistics.h).

#include <string>
#include <vector>

#include "analysis/fit/optimiser.h"
#include "analysis/fit/residuals.h"
#include "analysis/fit/statistics.h"

namespace mechflow::analysis::fit {

enum class Method { kLevenbergMarquardt, kDerivativeFree };

struct FitOptions {
  Method method = Method::kLevenbergMarquardt;
  int max_iterations = 100;   // Levenberg-Marquardt's
  int max_evaluations = 0;    // the derivative-free method's runs per experiment (0: 200 per parameter)
  double step = 1e-3;         // the optimiser's forward-difference step, a fraction of each parameter's range
  double statistics_step = 1e-4;  // the central differences' at the result, for the standard errors
};

struct FitResult {
  std::vector<double> start, values;  // per parameter, its unit
  std::vector<bool> at_bound;         // the value is on a bound (within 1e-6 of the range)
  Statistics statistics;
  double cost_before = 0.0, cost_after = 0.0;  // sums of squared weighted residuals
  int residuals = 0;
  long long runs = 0;                 // simulations run, the probe's included
  OptimiserResult optimiser;          // its cost history, report
  std::vector<std::string> failures;  // runs that failed during the fit, each once
  Evaluation initial, fitted;         // the simulated signals at the start and at the result
};

class Fitter {
 public:
  // Loads each experiment's model once and checks, before any run: the
  // parameters are identifiers defined by numbers, not set per experiment,
  // starting within their bounds (a start on a bound is moved inside, see
  // notes()); the matched signals are output ports; the measured times lie
  // within the runs. Throws InputError.
  explicit Fitter(Setup setup);

  const Setup& setup() const { return setup_; }
  const std::vector<std::string>& notes() const { return notes_; }

  // A run at the start and one per parameter moved by a hundredth of its
  // range: a parameter that changes no matched output is refused
  // (InputError "mu_d has no effect on m.x").
  void Probe();

  FitResult Run(const FitOptions& options);

  long long runs() const { return residuals_.runs(); }

 private:
  Setup setup_;
  std::vector<std::string> notes_;
  Residuals residuals_;
};

// The checks a Fitter makes before any run (not the start's bounds), for
// experiments to be scored; fills each parameter's start. InputError.
void CheckSetup(Setup* setup);

// The same matches of other experiments (--holdout) at given parameter
// values: the cost of data not used in fitting. `setup` as for a Fitter,
// its experiments the held-out ones; checked alike (InputError).
Evaluation Score(Setup setup, const std::vector<double>& values);

}  // namespace mechflow::analysis::fit
