#include "cli/fit_command.h"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>
#include <sstream>
#include <thread>

#include "analysis/fit/fit.h"
#include "blocks/outputs/csv.h"
#include "blocks/support/input_file.h"
#include "cli/fit_output.h"
#include "cli/interrupt.h"
#include "cli/output_claims.h"
#include "cli/output_folder.h"
#include "cli/ranks.h"
#include "cli/run_outputs.h"
#include "mech/errors.h"
#include "run/model.h"

namespace mechflow::cli {

const std::vector<std::string> kFitOptions = {"--data",   "--match",  "--free",       "--constraint",
                                              "--method", "--holdout", "--variant",   "--set"};

std::string FitHelp() {
  return "usage: mechflow fit FILE --data MEAS.csv [--variant V]... [--set NAME=VALUE]...\n"
         "                  [--data ...] --match SIGNAL=COLUMN[:WEIGHT]... --free NAME=LOWER:UPPER[:log]...\n"
         "                  [--constraint A<=B]... [--method lm|derivative-free]\n"
         "                  [--holdout OTHER.csv [--variant V]... [--set NAME=VALUE]...]\n"
         "                  [--jobs N] [--t-end T] [--out DIR] [--no-plot] [--overwrite]\n"
         "\n"
         "Fits identifiers of the diagram FILE (friction coefficients, stiffnesses) to\n"
         "measured data: least squares of WEIGHT * (simulated - measured) of every\n"
         "--match at exactly the measured times (the solver's output there, no\n"
         "interpolation), over every --data file, with one set of parameter values.\n"
         "Prints and writes NAME.fit.csv (parameter,value,standard_error,lower,upper,\n"
         "at_bound), the correlation matrix NAME.fit.correlation.csv, the cost before\n"
         "and after, the number of runs; NAME.fit.set holds the fitted values for\n"
         "`mechflow run FILE --set-file NAME.fit.set`. NAME.fit.dataK.csv and the plot\n"
         "NAME.fit.png show measured, start and fitted signals per experiment and the\n"
         "cost history. Standard errors are s^2 (J^T J)^-1 at the solution, s^2 the\n"
         "residuals' variance.\n"
         "\n"
         "  --data FILE       measurements: a CSV with a header, time [s] first, rising, every\n"
         "                    field a finite number (repeatable: experiments fitted together)\n"
         "  --variant, --set  before the first --data: for every experiment; after a --data\n"
         "                    or --holdout: for that one only (its test's load, speed, ...)\n"
         "  --match SIGNAL=COLUMN[:WEIGHT]  the output port SIGNAL (block.port) against the\n"
         "                    data's COLUMN, weighted (1/sigma of its noise; default 1);\n"
         "                    SIGNAL report:LABEL is a <report> figure's value, report-time:LABEL\n"
         "                    its time, against COLUMN's one value (one row, or the same in each)\n"
         "  --free NAME=LOWER:UPPER[:log]  an identifier defined by a number, fitted between\n"
         "                    the bounds (required; log: on a log scale), from its value in\n"
         "                    the diagram (moved inside when on a bound)\n"
         "  --method M        lm (default): Levenberg-Marquardt (Ceres) with forward\n"
         "                    differences, for smooth costs; derivative-free: BOBYQA (NLopt),\n"
         "                    for costs that stick/slip or contact make non-smooth\n"
         "  --constraint A<=B  between two free parameters (or A>=B): a point breaking it is\n"
         "                    not run, it counts as a failed run (repeatable)\n"
         "  --holdout FILE    data not used in fitting, scored at the fitted values\n"
         "  --jobs N          runs at a time (default: the number of cores)\n"
         "  --t-end T, --unsafe-lua, --allow-read, --library  as for mechflow run\n"
         "  --out DIR, --no-plot, --overwrite  as for mechflow run\n"
         "Refused before fitting: a parameter that moves no matched output, a start\n"
         "outside the bounds, measured times outside the run, a bad data row\n"
         "(file:line). A run that fails during the fit gives large residuals and a\n"
         "warning. Under mpirun (built with MPI), each round of runs is shared by the\n"
         "processes, each with --jobs threads; the result is the threaded one, bit for bit.\n"
         "\n"
         "Exit codes: 0 fitted, 1 stopped without converging (everything written),\n"
         "2 bad input, 130 / 143 ended by SIGINT / SIGTERM.\n";
}

namespace {

using analysis::fit::Experiment;
using analysis::fit::Setup;

struct DataSpec {
  std::string file;
  bool holdout = false;
  std::vector<std::string> variants;
  std::vector<std::pair<std::string, double>> overrides;
};

std::pair<std::string, double> ParseSet(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0) throw UsageError("--set expects NAME=VALUE, got '" + text + "'");
  return {text.substr(0, eq), ParseNumber(text.substr(eq + 1), "--set " + text.substr(0, eq))};
}

}  // namespace

namespace {

int Fit(const Arguments& args, const Ranks& ranks, std::ostream& out, std::ostream& err) {
  Setup setup;
  setup.diagram = args.file;
  setup.common.variants = args.variants;
  setup.common.overrides = args.overrides;
  setup.common.expression_overrides = args.set_expressions;
  setup.common.t_end = args.t_end;
  setup.common.unsafe_lua = args.unsafe_lua;
  setup.common.allow_read = args.allow_read;
  setup.common.library = args.library;
  std::vector<DataSpec> data;
  analysis::fit::Method method = analysis::fit::Method::kLevenbergMarquardt;
  std::vector<std::string> constraints;
  for (const auto& [option, value] : args.command_options) {
    if (option == "--data" || option == "--holdout") {
      data.push_back({value, option == "--holdout", {}, {}});
    } else if (option == "--variant") {
      (data.empty() ? setup.common.variants : data.back().variants).push_back(value);
    } else if (option == "--set") {
      (data.empty() ? setup.common.overrides : data.back().overrides).push_back(ParseSet(value));
    } else if (option == "--match") {
      setup.matches.push_back(analysis::fit::ParseMatch(value));
    } else if (option == "--free") {
      setup.parameters.push_back(analysis::fit::ParseFree(value));
    } else if (option == "--method") {
      if (value == "lm") method = analysis::fit::Method::kLevenbergMarquardt;
      else if (value == "derivative-free") method = analysis::fit::Method::kDerivativeFree;
      else throw UsageError("--method: '" + value + "' is not lm or derivative-free");
    } else if (option == "--constraint") {
      constraints.push_back(value);
    }
  }
  // after the loop: a constraint may name a --free given after it
  for (const std::string& c : constraints)
    setup.constraints.push_back(analysis::fit::ParseConstraint(c, setup.parameters));
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  setup.threads = args.jobs.value_or(std::max(1, cores / ranks.local_size()));
  if (ranks.size() > 1) {
    setup.processes.rank = ranks.rank();
    setup.processes.size = ranks.size();
    setup.processes.all_gather = [&ranks](const std::string& mine) { return ranks.AllGather(mine); };
  }
  // the diagram as given: its common options checked, its outputs' name
  run::Model base(args.file, setup.common);
  setup.description = base.description();
  const diagrams::LoadedDiagram& loaded = base.Loaded();
  const std::string stem = StemOf(loaded.csv_file);
  std::vector<Experiment> holdout;
  std::vector<std::string> experiment_files;
  for (const DataSpec& d : data) {
    Experiment e = analysis::fit::ReadExperiment(blocks::ReadInputFile(d.file, "data file"), d.file, setup.matches);
    e.variants = d.variants;
    e.overrides = d.overrides;
    (d.holdout ? holdout : setup.experiments).push_back(std::move(e));
  }
  const OutputFolder folder(args.out_dir);
  const InterruptHandlers handlers;
  setup.interrupt = InterruptFlag();
  const Setup holdout_setup = [&] {
    Setup h = setup;
    h.experiments = holdout;
    return h;
  }();
  analysis::fit::Fitter fitter(std::move(setup));
  if (!holdout.empty()) {  // checked before the fit: bad input
    Setup checked = holdout_setup;
    analysis::fit::CheckSetup(&checked);
  }
  ClaimStems(folder, args.file, {{stem, ResultsNameOrigin(loaded, std::nullopt)}}, args.overwrite, ranks.root(), out);
  const Setup& s = fitter.setup();
  std::size_t measured = 0;
  for (const Experiment& e : s.experiments)
    for (const auto& m : s.matches) measured += m.is_signal() ? e.times.size() : 1;
  out << "mechflow fit " << args.file << ": " << s.parameters.size() << " parameter"
      << (s.parameters.size() == 1 ? "" : "s") << ", " << s.experiments.size() << " experiment"
      << (s.experiments.size() == 1 ? "" : "s") << " (" << measured << " measured values), "
      << (method == analysis::fit::Method::kLevenbergMarquardt ? "Levenberg-Marquardt (Ceres)" : "BOBYQA (NLopt)")
      << ", " << s.threads << " run" << (s.threads == 1 ? "" : "s") << " at a time"
      << (ranks.size() > 1 ? " in each of " + std::to_string(ranks.size()) + " processes" : "") << "\n";
  for (const std::string& note : fitter.notes()) out << "note: " << note << "\n";
  const auto start = std::chrono::steady_clock::now();
  fitter.Probe();
  analysis::fit::FitOptions options;
  options.method = method;
  const analysis::fit::FitResult result = fitter.Run(options);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (const int signal = *InterruptFlag()) {
    err << "mechflow fit: interrupted by " << SignalName(signal) << "; nothing written\n";
    return 128 + signal;
  }
  const FitReport report{stem, args.file, &s, &result};
  std::ostringstream summary;  // printed, and written as NAME.fit.txt
  PrintFit(report, summary);
  summary << result.runs << " runs in " << blocks::CsvNumber(std::round(seconds * 100) / 100) << " s ("
      << static_cast<long long>(std::round(result.runs / std::max(seconds, 1e-9))) << " runs/s); "
      << result.optimiser.iterations << " iterations: " << result.optimiser.report << "\n";
  if (!holdout.empty()) {
    const analysis::fit::Evaluation scored = analysis::fit::Score(holdout_setup, result.values);
    std::size_t n = 0;
    for (const Experiment& e : holdout)
      for (const auto& m : s.matches) n += m.is_signal() ? e.times.size() : 1;
    summary << "holdout: cost " << blocks::CsvNumber(scored.Cost()) << " over " << n << " values (RMS weighted residual "
        << blocks::CsvNumber(std::sqrt(scored.Cost() / static_cast<double>(n))) << "; the fit's: "
        << blocks::CsvNumber(std::sqrt(result.cost_after / result.residuals)) << ")\n";
    for (const std::string& f : scored.failures) err << "warning: holdout: " << f << "\n";
  }
  out << summary.str();
  for (const auto& group : result.statistics.indistinct) {
    std::string names;
    for (const std::string& n : group) names += (names.empty() ? "" : ", ") + n;
    err << "warning: the data cannot tell apart " << names
        << " (the information matrix J^T J is near singular: a combination of them changes the matched signals "
           "hardly at all); their standard errors are not determined: fix all but one with --set, or add data "
           "that moves them differently\n";
  }
  if (!result.failures.empty()) {
    err << "warning: " << result.failures.size() << (result.failures.size() >= 20 ? " or more" : "")
        << " runs failed during the fit (large residuals there, the fit went on); the first: "
        << result.failures.front() << "\n";
  }
  for (std::size_t j = 0; j < result.at_bound.size(); ++j)
    if (result.at_bound[j])
      err << "warning: " << s.parameters[j].name << " ended on a bound (" << blocks::CsvNumber(result.values[j])
          << "); the data may want it beyond: widen its bounds if they allow\n";
  std::string warning;
  if (ranks.root())  // the others hold the same numbers
    for (const std::string& name : WriteFit(report, summary.str(), folder, !args.no_plot, &warning))
      out << "wrote " << folder.PathOf(name) << "\n";
  if (!warning.empty()) err << "warning: no plot: " << warning << "\n";
  return result.optimiser.converged ? 0 : 1;
}

}  // namespace

int FitCommand(const Arguments& args, std::ostream& out, std::ostream& err) {
  std::unique_ptr<Ranks> ranks;
  try {
    ranks = std::make_unique<Ranks>();
  } catch (const std::exception& e) {
    err << "mechflow fit: " << e.what() << "\n";
    return 2;
  }
  // every process runs the same fit; only the first prints and writes
  std::ostream null_stream(nullptr);
  std::ostream& here_out = ranks->root() ? out : null_stream;
  std::ostream& here_err = ranks->root() ? err : null_stream;
  try {
    return Fit(args, *ranks, here_out, here_err);
  } catch (const InputError& e) {
    here_err << e.what() << "\n";
    return 2;
  } catch (const UsageError& e) {
    here_err << "mechflow fit: " << e.what() << "\n";
    return 2;
  }
}

}  // namespace mechflow::cli
