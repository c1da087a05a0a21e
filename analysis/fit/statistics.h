#pragma once
// Standard errors and correlations of fitted parameters from the Jacobian at
// the solution: covariance s^2 (J^T J)^-1 with s^2 = |r|^2 / (m - n), the
// residuals' variance (m residuals, n parameters), as the Gauss-Newton
// approximation of the cost's curvature gives it; mapped from the unit box
// to the parameters' own units by each parameter's slope d value / d u.
//
// The information matrix J^T J is judged scaled to a unit diagonal (the
// correlation form, so that units do not matter): an eigenvalue below 1e-6
// of the largest means the data move some combination of the parameters
// hardly at all. The parameters that make up that combination cannot be told
// apart; their standard errors are not to be trusted (NaN when singular).

#include <string>
#include <vector>

#include <Eigen/Dense>

#include "analysis/fit/parameters.h"

namespace mechflow::analysis::fit {

struct Statistics {
  std::vector<double> standard_error;  // per parameter, its unit; NaN when not determined
  Eigen::MatrixXd correlation;         // n x n; NaN when some cannot be told apart
  double variance = 0.0;               // s^2
  // each group of parameters the data cannot tell apart (empty: all told apart)
  std::vector<std::vector<std::string>> indistinct;
};

Statistics Estimate(const std::vector<FreeParameter>& parameters, const std::vector<double>& u,
                    const Eigen::MatrixXd& jacobian, const Eigen::VectorXd& residuals);

}  // namespace mechflow::analysis::fit
