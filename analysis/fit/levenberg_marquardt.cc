// Ceres' bounded Levenberg-Marquardt on the fit's objective.

#include <algorithm>

#include <ceres/ceres.h>

#include "analysis/fit/optimiser.h"

namespace mechflow::analysis::fit {
namespace {

// The residuals of all experiments as one Ceres residual block of one
// parameter block (u); its Jacobian is the Objective's forward differences.
class RunsCost final : public ceres::CostFunction {
 public:
  explicit RunsCost(Objective& objective) : objective_(objective) {
    set_num_residuals(objective.size());
    mutable_parameter_block_sizes()->push_back(objective.parameters());
  }
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const int n = objective_.parameters(), m = objective_.size();
    std::vector<double> u(parameters[0], parameters[0] + n);
    for (double& x : u) x = std::clamp(x, 0.0, 1.0);  // Ceres keeps to the bounds; rounding aside
    if (jacobians && jacobians[0]) {
      Eigen::VectorXd r;
      Eigen::MatrixXd j;
      objective_.Linearise(u, &r, &j);
      std::copy(r.data(), r.data() + m, residuals);
      Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(jacobians[0], m, n) = j;
    } else {
      const std::vector<double>& r = objective_.At(u).residuals;
      std::copy(r.begin(), r.end(), residuals);
    }
    return true;
  }

 private:
  Objective& objective_;
};

// The cost after each iteration; stops at Ctrl-C.
class Watch final : public ceres::IterationCallback {
 public:
  Watch(std::vector<double>* history, const volatile std::sig_atomic_t* interrupt)
      : history_(history), interrupt_(interrupt) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& s) override {
    if (s.step_is_successful || s.iteration == 0) history_->push_back(2.0 * s.cost);  // Ceres' cost is half
    return interrupt_ && *interrupt_ ? ceres::SOLVER_ABORT : ceres::SOLVER_CONTINUE;
  }

 private:
  std::vector<double>* history_;
  const volatile std::sig_atomic_t* interrupt_;
};

}  // namespace

OptimiserResult LevenbergMarquardt(Objective& objective, const std::vector<double>& start, int max_iterations,
                                   const volatile std::sig_atomic_t* interrupt) {
  OptimiserResult result;
  result.u = start;
  const int n = objective.parameters();
  ceres::Problem::Options problem_options;
  problem_options.cost_function_ownership = ceres::TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  problem.AddResidualBlock(new RunsCost(objective), nullptr, result.u.data());
  for (int j = 0; j < n; ++j) {
    problem.SetParameterLowerBound(result.u.data(), j, 0.0);
    problem.SetParameterUpperBound(result.u.data(), j, 1.0);
  }
  ceres::Solver::Options options;
  options.minimizer_type = ceres::TRUST_REGION;
  options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = max_iterations;
  // a simulation's outputs are good to its tolerances, not to rounding
  options.function_tolerance = 1e-10;
  options.parameter_tolerance = 1e-9;
  options.gradient_tolerance = 1e-14;
  options.num_threads = 1;  // the runs are parallel; the linear algebra is small
  options.logging_type = ceres::SILENT;
  Watch watch(&result.history, interrupt);
  options.callbacks.push_back(&watch);
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  result.iterations = static_cast<int>(summary.iterations.size()) - 1;
  result.converged = summary.termination_type == ceres::CONVERGENCE;
  result.interrupted = summary.termination_type == ceres::USER_FAILURE && interrupt && *interrupt;
  result.report = summary.message;
  for (double& x : result.u) x = std::clamp(x, 0.0, 1.0);
  return result;
}

}  // namespace mechflow::analysis::fit
