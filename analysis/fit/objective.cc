#include "analysis/fit/objective.h"

#include <algorithm>

namespace mechflow::analysis::fit {

void Objective::Keep(const std::vector<double>& u, const Evaluation& e) {
  for (const std::string& f : e.failures)
    if (failures_.size() < 20) failures_.insert(f);
  last_u_ = u;
  last_ = e;
  have_last_ = true;
}

const Evaluation& Objective::At(const std::vector<double>& u) {
  if (have_last_ && u == last_u_) return last_;
  const Evaluation e = residuals_.EvaluateUnit({u}).front();
  Keep(u, e);
  return last_;
}

void Objective::Linearise(const std::vector<double>& u, Eigen::VectorXd* r, Eigen::MatrixXd* jacobian) {
  const int n = parameters();
  std::vector<std::vector<double>> points;
  const bool known = have_last_ && u == last_u_;
  if (!known) points.push_back(u);
  std::vector<double> h(n);
  for (int j = 0; j < n; ++j) {
    std::vector<double> p = u;
    h[j] = u[j] + step_ <= 1.0 ? step_ : -step_;  // inside the bounds: backwards at the upper one
    p[j] += h[j];
    points.push_back(std::move(p));
  }
  const std::vector<Evaluation> e = residuals_.EvaluateUnit(points);
  if (!known) {
    Keep(u, e.front());
  }
  const std::vector<double>& base = last_.residuals;
  *r = Eigen::Map<const Eigen::VectorXd>(base.data(), static_cast<Eigen::Index>(base.size()));
  jacobian->resize(size(), n);
  const std::size_t offset = known ? 0 : 1;
  for (int j = 0; j < n; ++j) {
    const std::vector<double>& moved = e[offset + j].residuals;
    for (int i = 0; i < size(); ++i) (*jacobian)(i, j) = (moved[i] - base[i]) / h[j];
    for (const std::string& f : e[offset + j].failures)
      if (failures_.size() < 20) failures_.insert(f);
  }
}

Eigen::MatrixXd Objective::CentralJacobian(const std::vector<double>& u, double step) {
  const int n = parameters();
  std::vector<std::vector<double>> points;
  std::vector<double> width(n);
  for (int j = 0; j < n; ++j) {
    // within the bounds: one side shortened at a bound
    const double below = std::min(step, u[j]), above = std::min(step, 1.0 - u[j]);
    std::vector<double> p = u;
    p[j] = u[j] + above;
    points.push_back(p);
    p[j] = u[j] - below;
    points.push_back(p);
    width[j] = above + below;
  }
  const std::vector<Evaluation> e = residuals_.EvaluateUnit(points);
  Eigen::MatrixXd jacobian(size(), n);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < size(); ++i) jacobian(i, j) = (e[2 * j].residuals[i] - e[2 * j + 1].residuals[i]) / width[j];
    for (const Evaluation& side : {e[2 * j], e[2 * j + 1]})
      for (const std::string& f : side.failures)
        if (failures_.size() < 20) failures_.insert(f);
  }
  return jacobian;
}

}  // namespace mechflow::analysis::fit
