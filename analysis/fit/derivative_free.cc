// NLopt's BOBYQA (Nelder-Mead for one parameter) on the fit's objective.

#include <algorithm>
#include <limits>

#include <nlopt.h>

#include "analysis/fit/optimiser.h"

namespace mechflow::analysis::fit {
namespace {

struct Context {
  Objective* objective;
  OptimiserResult* result;
  double best = std::numeric_limits<double>::infinity();
  const volatile std::sig_atomic_t* interrupt;
  nlopt_opt opt;
};

double Cost(unsigned n, const double* x, double* gradient, void* data) {
  (void)gradient;  // a derivative-free method asks for none
  Context& c = *static_cast<Context*>(data);
  if (c.interrupt && *c.interrupt) nlopt_force_stop(c.opt);
  std::vector<double> u(x, x + n);
  for (double& v : u) v = std::clamp(v, 0.0, 1.0);
  const double cost = c.objective->At(u).Cost();
  if (cost < c.best) {
    c.best = cost;
    c.result->u = u;
  }
  c.result->history.push_back(c.best);  // the best so far after each evaluation
  ++c.result->iterations;
  return cost;
}

}  // namespace

OptimiserResult DerivativeFree(Objective& objective, const std::vector<double>& start, int max_evaluations,
                               const volatile std::sig_atomic_t* interrupt) {
  OptimiserResult result;
  result.u = start;
  const unsigned n = static_cast<unsigned>(objective.parameters());
  nlopt_opt opt = nlopt_create(n >= 2 ? NLOPT_LN_BOBYQA : NLOPT_LN_NELDERMEAD, n);
  Context context{&objective, &result, std::numeric_limits<double>::infinity(), interrupt, opt};
  nlopt_set_lower_bounds1(opt, 0.0);
  nlopt_set_upper_bounds1(opt, 1.0);
  nlopt_set_min_objective(opt, Cost, &context);
  nlopt_set_xtol_abs1(opt, 1e-7);
  nlopt_set_ftol_rel(opt, 1e-12);
  nlopt_set_maxeval(opt, max_evaluations);
  nlopt_set_initial_step1(opt, 0.1);  // a tenth of each range
  std::vector<double> x = start;
  double minimum = 0.0;
  const nlopt_result status = nlopt_optimize(opt, x.data(), &minimum);
  nlopt_destroy(opt);
  result.converged = status == NLOPT_XTOL_REACHED || status == NLOPT_FTOL_REACHED || status == NLOPT_SUCCESS;
  result.interrupted = status == NLOPT_FORCED_STOP;
  result.report = status == NLOPT_MAXEVAL_REACHED ? "stopped after " + std::to_string(max_evaluations) + " runs"
                  : status == NLOPT_XTOL_REACHED  ? "the parameters changed by less than 1e-7 of their ranges"
                  : status == NLOPT_FTOL_REACHED  ? "the cost changed by less than 1e-12 of itself"
                  : status < 0                    ? std::string("NLopt stopped: ") + nlopt_result_to_string(status)
                                                  : std::string(nlopt_result_to_string(status));
  return result;
}

}  // namespace mechflow::analysis::fit
