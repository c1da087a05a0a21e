#pragma once
// The residuals of a fit: for every experiment, every match and every
// measured instant, WEIGHT * (simulated - measured), in that order (a
// <report> figure's match: one residual per experiment). One
// point of parameters takes one run per experiment; many points are run
// together on the batch's threads (run/batch.h), each experiment's model
// made once per thread and rebuilt with each point's values.
//
// A run that fails (solver failure, a value the model refuses, a script
// error) or stops before the last measured time leaves the instants it did
// not reach without a simulated value: each of them gets a large residual,
// ten times the largest measured magnitude of its column (weighted), so the
// optimiser backs away from such parameters, and the failure is kept as a
// message; the fit does not stop.

#include <csignal>
#include <functional>
#include <set>
#include <string>
#include <vector>

#include "analysis/fit/constraint.h"
#include "analysis/fit/experiment.h"
#include "analysis/fit/parameters.h"
#include "run/batch.h"

namespace mechflow::analysis::fit {

// Processes sharing a fit's runs (MPI ranks, from the command line): point p
// of each round of runs is run by process p mod size, on its threads, and
// every process gets every point's evaluation through all_gather, so all
// run the same optimiser on the same numbers and end with the same result,
// the one a single process gives, bit for bit. One process: size 1.
struct Processes {
  int rank = 0, size = 1;
  std::function<std::vector<std::string>(const std::string&)> all_gather;  // collective
};

// What a fit is given: the diagram, what to match, where, and what is free.
struct Setup {
  std::string diagram;                      // the file, for messages
  diagrams::DiagramDescription description;  // read once
  run::LoadOptions common;                  // sandbox, --t-end, the common variants and --set
  std::vector<Match> matches;
  std::vector<Experiment> experiments;
  std::vector<FreeParameter> parameters;
  std::vector<Constraint> constraints;  // between parameters: a point breaking one is not run
  int threads = 1;
  Processes processes;
  const volatile std::sig_atomic_t* interrupt = nullptr;  // Ctrl-C: runs end (failed)
};

// The simulated signals and residuals of one point.
struct Evaluation {
  std::vector<double> residuals;
  // [experiment][match][instant] (a figure: its one value); NaN where the run did not get to
  std::vector<std::vector<std::vector<double>>> simulated;
  std::vector<std::string> failures;  // a message per run that failed or stopped short
  double Cost() const;               // the sum of squared residuals
};

class Residuals {
 public:
  explicit Residuals(const Setup& setup);

  int size() const { return size_; }
  const Setup& setup() const { return setup_; }

  // Runs every point of physical parameter values together.
  std::vector<Evaluation> Evaluate(const std::vector<std::vector<double>>& points);
  // The same, given as unit points u (analysis/fit/parameters.h).
  std::vector<Evaluation> EvaluateUnit(const std::vector<std::vector<double>>& points);

  long long runs() const { return runs_; }  // by every process
  int threads() const { return batch_.threads(); }

 private:
  std::vector<Evaluation> EvaluateHere(const std::vector<std::vector<double>>& points);
  Evaluation Collect(const std::vector<double>& values, const std::vector<run::BatchOutcome>& outcomes,
                     std::size_t first) const;

  const Setup& setup_;
  int size_ = 0;
  std::vector<std::string> signals_;  // logged, each once
  std::vector<int> column_;           // per match: its column in a run's rows (time is 0)
  std::vector<double> penalty_;       // per match: the residual of an instant not reached
  long long runs_ = 0;
  bool figures_ = false;              // some match is a <report> figure: runs go to the diagram's t_end
  run::Batch batch_;
};

// The batch's models: one per experiment, the common options then its own.
std::vector<run::BatchModel> ExperimentModels(const Setup& setup);

}  // namespace mechflow::analysis::fit
