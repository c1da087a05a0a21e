#include "analysis/fit/fit.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "blocks/outputs/csv.h"
#include "blocks/support/excerpt.h"
#include "blocks/support/suggest.h"
#include "diagrams/units.h"
#include "mech/errors.h"
#include "scripting/identifiers.h"

namespace mechflow::analysis::fit {

void CheckSetup(Setup* setup) {
  if (setup->experiments.empty()) throw InputError("no measured data: give --data FILE");
  if (setup->matches.empty()) throw InputError("nothing to compare: give --match SIGNAL=COLUMN");
  const std::vector<run::BatchModel> models = ExperimentModels(*setup);
  for (std::size_t e = 0; e < models.size(); ++e) {
    const Experiment& experiment = setup->experiments[e];
    run::Model model(models[e].description, models[e].options);  // variants, --set: refused here if bad
    for (const auto& [name, value] : experiment.overrides)
      for (const FreeParameter& p : setup->parameters)
        if (scripting::ToLower(name) == scripting::ToLower(p.name))
          throw InputError("--set " + name + " after --data " + experiment.file + ": " + p.name +
                           " is a free parameter, fitted to all the data; leave it out of --set, or fit it in a "
                           "separate run");
    const std::vector<run::Identifier> ids = model.Identifiers();
    for (FreeParameter& p : setup->parameters) {
      model.Set(p.name, p.lower);  // an unknown or derived identifier is refused in --set's words
      if (e > 0) continue;
      for (const run::Identifier& id : ids) {
        if (scripting::ToLower(id.name) != scripting::ToLower(p.name)) continue;
        // the value is SI; bounds and --set are in the unit of its definition (N/mm)
        std::string error;
        const std::optional<diagrams::Unit> unit =
            id.unit.empty() ? std::nullopt : diagrams::ParseUnit(id.unit, &error);
        p.start = unit ? id.value / unit->to_si : id.value;
      }
    }
    const std::vector<std::string> loggable = model.LoggableSignals();
    const diagrams::LoadedDiagram& loaded = model.Loaded();
    for (const Match& m : setup->matches) {
      if (!m.is_signal()) {
        std::vector<std::string> labels;
        for (const blocks::ReportRequest& r : loaded.reports) labels.push_back(r.label);
        if (std::find(labels.begin(), labels.end(), m.figure) == labels.end())
          throw InputError("--match " + m.signal + "=" + m.column + ": " + setup->diagram + " has no <report> '" +
                           blocks::Excerpt(m.figure) + "'" + blocks::DidYouMean(m.figure, labels) +
                           (labels.empty() ? "; it has none" : "; its reports: " + blocks::JoinNames(labels)));
        continue;
      }
      const std::string port = m.signal.substr(0, m.signal.find('['));
      if (std::find(loggable.begin(), loggable.end(), port) == loggable.end())
        throw InputError("--match " + m.signal + "=" + m.column + ": " + setup->diagram + " has no output port '" +
                         blocks::Excerpt(m.signal) + "'" + blocks::DidYouMean(m.signal, loggable) +
                         " (give block.port, as <log signal> does)");
    }
    CheckTimesInRun(experiment, loaded.solver.t_start, loaded.solver.t_end);
  }
}

namespace {

// Within a hundredth of its range of a bound: moved to there, so the first
// differences and steps can go both ways.
void MoveInside(std::vector<FreeParameter>* parameters, std::vector<std::string>* notes) {
  for (FreeParameter& p : *parameters) {
    const double u = p.ToUnit(p.start);
    if (!(u >= 0.0 && u <= 1.0))
      throw InputError("--free " + p.name + ": its value in the diagram, " + blocks::CsvNumber(p.start) +
                       ", is outside the bounds " + blocks::CsvNumber(p.lower) + " to " + blocks::CsvNumber(p.upper) +
                       "; the fit starts there: widen the bounds, or give a start inside with --set " + p.name +
                       "=VALUE before the first --data");
    if (u < 0.01 || u > 0.99) {
      const double moved = p.FromUnit(std::clamp(u, 0.01, 0.99));
      notes->push_back("the start of " + p.name + ", " + blocks::CsvNumber(p.start) + ", is on a bound; moved inside to " +
                       blocks::CsvNumber(moved));
      p.start = moved;
    }
  }
}

}  // namespace

Fitter::Fitter(Setup setup) : setup_([&] {
  if (setup.parameters.empty()) throw InputError("nothing to fit: give --free NAME=LOWER:UPPER");
  for (std::size_t j = 0; j < setup.parameters.size(); ++j)
    for (std::size_t k = 0; k < j; ++k)
      if (scripting::ToLower(setup.parameters[j].name) == scripting::ToLower(setup.parameters[k].name))
        throw InputError("--free " + setup.parameters[j].name + " is given twice");
  return std::move(setup);
}()), residuals_(setup_) {
  CheckSetup(&setup_);
  MoveInside(&setup_.parameters, &notes_);
}

void Fitter::Probe() {
  std::vector<double> start;
  for (const FreeParameter& p : setup_.parameters) start.push_back(p.start);
  if (const std::string broken = Broken(setup_.constraints, setup_.parameters, start); !broken.empty())
    throw InputError("the start values break a constraint: " + broken +
                     "; start elsewhere (--set NAME=VALUE before the first --data)");
  const std::size_t n = setup_.parameters.size();
  std::vector<std::vector<double>> points;
  std::vector<double> u0(n);
  for (std::size_t j = 0; j < n; ++j) u0[j] = setup_.parameters[j].ToUnit(setup_.parameters[j].start);
  points.push_back(u0);
  for (std::size_t j = 0; j < n; ++j) {
    std::vector<double> u = u0;
    u[j] += u[j] + 0.01 <= 1.0 ? 0.01 : -0.01;
    points.push_back(u);
  }
  const std::vector<Evaluation> e = residuals_.EvaluateUnit(points);
  if (!e.front().failures.empty())
    throw InputError("the run at the start values failed: " + e.front().failures.front() +
                     "; start elsewhere (--set NAME=VALUE before the first --data)");
  for (std::size_t j = 0; j < n; ++j) {
    if (!e[j + 1].failures.empty()) continue;  // it has an effect: the run failed
    bool moved = false;
    for (std::size_t i = 0; i < e.front().residuals.size(); ++i)
      moved = moved || e[j + 1].residuals[i] != e.front().residuals[i];
    if (moved) continue;
    std::string signals;
    for (const Match& m : setup_.matches)
      if (signals.find(m.signal) == std::string::npos) signals += (signals.empty() ? "" : ", ") + m.signal;
    throw InputError(setup_.parameters[j].name + " has no effect on " + signals + " (moving it by a hundredth of " +
                     "its range from " + blocks::CsvNumber(setup_.parameters[j].start) +
                     " changed no matched value at any measured time): it cannot be fitted to these data; leave "
                     "out --free " + setup_.parameters[j].name);
  }
}

FitResult Fitter::Run(const FitOptions& options) {
  const std::size_t n = setup_.parameters.size();
  FitResult result;
  std::vector<double> u0(n);
  for (std::size_t j = 0; j < n; ++j) {
    result.start.push_back(setup_.parameters[j].start);
    u0[j] = setup_.parameters[j].ToUnit(setup_.parameters[j].start);
  }
  Objective objective(residuals_, options.step);
  result.initial = objective.At(u0);
  result.cost_before = result.initial.Cost();
  result.residuals = residuals_.size();
  result.optimiser =
      options.method == Method::kLevenbergMarquardt
          ? LevenbergMarquardt(objective, u0, options.max_iterations, setup_.interrupt)
          : DerivativeFree(objective, u0, options.max_evaluations > 0 ? options.max_evaluations : 200 * static_cast<int>(n),
                           setup_.interrupt);
  const std::vector<double>& u = result.optimiser.u;
  result.fitted = objective.At(u);
  const std::vector<double>& fitted = result.fitted.residuals;
  const Eigen::VectorXd r = Eigen::Map<const Eigen::VectorXd>(fitted.data(), static_cast<Eigen::Index>(fitted.size()));
  const Eigen::MatrixXd jacobian = objective.CentralJacobian(u, options.statistics_step);
  result.cost_after = result.fitted.Cost();
  result.statistics = Estimate(setup_.parameters, u, jacobian, r);
  result.values = FromUnit(setup_.parameters, u);
  for (std::size_t j = 0; j < n; ++j) result.at_bound.push_back(u[j] <= 1e-6 || u[j] >= 1.0 - 1e-6);
  result.failures.assign(objective.failures().begin(), objective.failures().end());
  result.runs = residuals_.runs();
  return result;
}

Evaluation Score(Setup setup, const std::vector<double>& values) {
  CheckSetup(&setup);
  Residuals residuals(setup);
  return residuals.Evaluate({values}).front();
}

}  // namespace mechflow::analysis::fit
