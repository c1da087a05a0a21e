#pragma once
// The fit's objective as the optimisers see it: residuals of unit points u
// (analysis/fit/parameters.h), the sum of their squares, and the Jacobian by
// forward differences. A Jacobian's runs -- the point and one per parameter
// -- go to the batch together, so they run in parallel; the point last
// evaluated is remembered, since Levenberg-Marquardt asks for the residuals
// of a step and, once it is taken, for the Jacobian there.

#include <set>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "analysis/fit/residuals.h"

namespace mechflow::analysis::fit {

class Objective {
 public:
  // `step`: the forward difference step in u (a fraction of each range).
  Objective(Residuals& residuals, double step) : residuals_(residuals), step_(step) {}

  int parameters() const { return static_cast<int>(residuals_.setup().parameters.size()); }
  int size() const { return residuals_.size(); }

  const Evaluation& At(const std::vector<double>& u);
  // The residuals at `u` and the Jacobian d r / d u (size() x parameters()).
  void Linearise(const std::vector<double>& u, Eigen::VectorXd* r, Eigen::MatrixXd* jacobian);
  // The Jacobian by central differences of `step` (2 runs per parameter):
  // the local slope the standard errors need, where the optimiser's larger
  // forward step would average over a cost that curves.
  Eigen::MatrixXd CentralJacobian(const std::vector<double>& u, double step);

  // Every failure message met, each once (the first of many alike kept short).
  const std::set<std::string>& failures() const { return failures_; }

 private:
  void Keep(const std::vector<double>& u, const Evaluation& e);

  Residuals& residuals_;
  double step_;
  std::vector<double> last_u_;
  Evaluation last_;
  bool have_last_ = false;
  std::set<std::string> failures_;
};

}  // namespace mechflow::analysis::fit
