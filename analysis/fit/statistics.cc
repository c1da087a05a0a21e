#include "analysis/fit/statistics.h"

#include <cmath>
#include <limits>

namespace mechflow::analysis::fit {

Statistics Estimate(const std::vector<FreeParameter>& parameters, const std::vector<double>& u,
                    const Eigen::MatrixXd& jacobian, const Eigen::VectorXd& residuals) {
  const Eigen::Index n = jacobian.cols(), m = jacobian.rows();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Statistics s;
  s.variance = m > n ? residuals.squaredNorm() / static_cast<double>(m - n) : nan;
  const Eigen::MatrixXd information = jacobian.transpose() * jacobian;
  // scaled to a unit diagonal; a parameter that moves nothing stays 0
  Eigen::VectorXd scale(n);
  for (Eigen::Index j = 0; j < n; ++j) scale(j) = information(j, j) > 0 ? 1.0 / std::sqrt(information(j, j)) : 0.0;
  const Eigen::MatrixXd scaled = scale.asDiagonal() * information * scale.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(scaled);
  const Eigen::VectorXd& lambda = eigen.eigenvalues();  // ascending
  const double largest = lambda.size() ? lambda(n - 1) : 0.0;
  std::vector<bool> undetermined(n, false);
  for (Eigen::Index k = 0; k < n; ++k) {
    if (lambda(k) > 1e-6 * largest) break;
    std::vector<std::string> group;
    for (Eigen::Index j = 0; j < n; ++j) {
      if (std::abs(eigen.eigenvectors()(j, k)) > 0.1 || scale(j) == 0.0) {
        group.push_back(parameters[j].name);
        undetermined[j] = true;
      }
    }
    s.indistinct.push_back(group);
  }
  // covariance in u: s^2 D (D J^T J D)^-1 D, then in the parameters' units
  Eigen::MatrixXd covariance = Eigen::MatrixXd::Constant(n, n, nan);
  if (s.indistinct.empty() && n > 0) {
    covariance = s.variance * scale.asDiagonal() * scaled.inverse() * scale.asDiagonal();
    for (Eigen::Index i = 0; i < n; ++i)
      for (Eigen::Index j = 0; j < n; ++j) covariance(i, j) *= parameters[i].Slope(u[i]) * parameters[j].Slope(u[j]);
  }
  s.standard_error.resize(n);
  s.correlation = Eigen::MatrixXd::Constant(n, n, nan);
  for (Eigen::Index i = 0; i < n; ++i) {
    s.standard_error[i] = undetermined[i] ? nan : std::sqrt(covariance(i, i));
    for (Eigen::Index j = 0; j < n; ++j)
      s.correlation(i, j) = covariance(i, j) / std::sqrt(covariance(i, i) * covariance(j, j));
  }
  return s;
}

}  // namespace mechflow::analysis::fit
