#include "cli/commands.h"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <optional>
#include <csignal>
#include <cstdio>
#include <sstream>
#include <string>

#include "analysis/modes.h"
#include "blocks/library/mechanism_block.h"
#include "cli/animation_output.h"
#include "cli/fit_command.h"
#include "cli/force_analysis_command.h"
#include "cli/interrupt.h"
#include "cli/modes_report.h"
#include "cli/output_claims.h"
#include "cli/output_budget.h"
#include "cli/output_folder.h"
#include "cli/plot_envelope.h"
#include "cli/export_fmu_command.h"
#include "cli/psd_command.h"
#include "cli/report.h"
#include "cli/results_file.h"
#include "cli/run_outputs.h"
#include "cli/sweep.h"
#include "diagrams/loader.h"
#include "graphics/scene.h"
#include "mech/errors.h"
#include "run/model.h"

namespace mechflow::cli {
namespace {

diagrams::LoadOptions ToLoadOptions(const Arguments& args) {
  diagrams::LoadOptions o;
  o.variants = args.variants;
  o.overrides = args.overrides;
  o.expression_overrides = args.set_expressions;
  o.t_end = args.t_end;
  o.rtol = args.rtol;
  o.atol = args.atol;
  o.interval = args.interval;
  if (args.results != "-") o.results = args.results;  // "-": standard output; the other files keep the diagram's names
  o.unsafe_lua = args.unsafe_lua;
  o.allow_read = args.allow_read;
  o.library = args.library;
  return o;
}

// A one-line progress display on a terminal: shown only once a run has taken
// more than a second, refreshed at most ten times a second, erased at the end.
class Progress {
 public:
  Progress(double t_start, double t_end)
      : t_start_(t_start), t_end_(t_end), enabled_(isatty(STDERR_FILENO)), start_(Clock::now()), last_(start_) {}
  ~Progress() {
    if (shown_) std::fprintf(stderr, "\r%*s\r", 70, "");
  }
  void operator()(double t) {
    if (!enabled_) return;
    const auto now = Clock::now();
    if (now - start_ < std::chrono::seconds(1) || now - last_ < std::chrono::milliseconds(100)) return;
    last_ = now;
    shown_ = true;
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    std::fprintf(stderr, "\r  t = %-12.6g s  %5.1f %%  %8.1f s elapsed ", t,
                 100.0 * (t - t_start_) / (t_end_ - t_start_), elapsed);
  }

 private:
  using Clock = std::chrono::steady_clock;
  double t_start_, t_end_;
  bool enabled_;
  bool shown_ = false;
  Clock::time_point start_, last_;
};

}  // namespace

// The loader's warnings (units that disagree), each on its line; their count.
int PrintLoadWarnings(const diagrams::LoadedDiagram& loaded, std::ostream& out) {
  for (const std::string& warning : loaded.warnings) out << warning << "\n";
  return static_cast<int>(loaded.warnings.size());
}

int RunCommand(const Arguments& args, std::ostream& out, std::ostream& err) {
  // --results -: standard output carries the results and nothing else
  std::optional<StandardOutputForResults> results_on_stdout;
  if (args.results == "-") results_on_stdout.emplace();
  run::Model model(args.file, ToLoadOptions(args));
  PrintLoadWarnings(model.Loaded(), err);
  // before the run: a bad --out is bad input. --results - without --out writes no file
  std::optional<OutputFolder> folder;
  if (!results_on_stdout || args.out_given) folder.emplace(args.out_dir);
  RunOutputPlan plan;
  plan.folder = folder ? &*folder : nullptr;
  plan.plot = !args.no_plot && !results_on_stdout;  // gnuplot draws from the results file
  // the rows go to the results file; the columns of the <spectrum>s stay in memory too
  std::unique_ptr<ResultsFile> results_file;
  run::RunOptions options;
  for (const diagrams::SpectrumRequest& s : model.Loaded().spectra) options.keep.push_back(s.column);
  options.interrupt = InterruptFlag();
  std::optional<Progress> progress;
  options.progress = [&](double t) {
    (*progress)(t);
    // past the budget (more rows than estimated): the run ends, its rows kept
    if (!results_file->stopped().empty()) throw SimulationError(results_file->stopped());
  };
  run::PreparedRun prepared = model.Prepare(options);
  const diagrams::LoadedDiagram& loaded = prepared.loaded();
  blocks::Simulator& sim = prepared.simulator();
  Arguments animation_args = args;
  if (!folder) animation_args.no_animate = true;  // nowhere to write it (said below)
  const AnimationOutput animation(loaded, animation_args, &sim);  // shapes checked now: bad geometry is bad input
  // every file estimated before any is made: past its budget is bad input
  const std::uint64_t budget = args.max_output_bytes.value_or(kDefaultMaxOutputBytes);
  const OutputEstimate csv_size = EstimateResultsCsv(sim.options(), sim.results().num_columns(),
                                                    results_on_stdout ? "standard output" : loaded.csv_file);
  RefuseOverBudget(csv_size, budget);
  const std::uint64_t animation_budget = args.max_output_bytes.value_or(kDefaultMaxAnimationBytes);
  for (const OutputEstimate& file : animation.EstimateSizes(csv_size.rows))
    RefuseOverBudget(file, animation_budget);
  // the plot of a long run is drawn from an envelope of its rows
  std::unique_ptr<PlotEnvelope> envelope;
  if (plan.plot && !loaded.plot_file.empty()) {
    std::vector<int> xy_columns;
    for (const diagrams::XYPlotRequest& p : loaded.xy_plots)
      for (const auto& [x, y] : p.curves) xy_columns.insert(xy_columns.end(), {x, y});
    std::sort(xy_columns.begin(), xy_columns.end());
    xy_columns.erase(std::unique(xy_columns.begin(), xy_columns.end()), xy_columns.end());
    envelope = std::make_unique<PlotEnvelope>(PlottedColumns(loaded.groups), xy_columns,
                                              loaded.solver.t_end - loaded.solver.t_start, nullptr);
  }
  // another diagram file's results in the folder are not overwritten unasked
  if (folder) {
    std::vector<OutputStem> stems = RunStems(loaded, plan, args.results);
    for (const OutputStem& s : animation.Stems()) stems.push_back(s);
    ClaimStems(*folder, args.file, stems, args.overwrite, true, out);
  }
  if (results_on_stdout) {
    SayWhatStandardOutputLeavesOut(loaded, plan, args.no_plot, out);
    plan.results_fd = results_on_stdout->TakeResultsDescriptor();
  }
  results_file = OpenResults(loaded, sim, plan, budget, envelope.get());
  const InterruptHandlers handlers;  // Ctrl-C, SIGTERM, SIGHUP: cli/interrupt.h

  const auto wall_start = std::chrono::steady_clock::now();
  progress.emplace(loaded.solver.t_start, loaded.solver.t_end);
  const blocks::RunOutcome outcome =
      prepared.Run(envelope ? static_cast<blocks::RowSink*>(envelope.get()) : results_file.get()).outcome;
  progress.reset();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();

  out << "mechflow run " << args.file << ": t = " << loaded.solver.t_start << " .. " << loaded.solver.t_end << " s\n";
  if (outcome.stopped) {
    out << "stopped by the control script at t = " << outcome.t_reached << " s: " << outcome.stop_reason
        << " (" << wall << " s of wall time)\n";
  } else if (outcome.ok) {
    out << "finished in " << wall << " s of wall time\n";
  } else if (outcome.interrupted) {
    err << outcome.failure << " at t = " << outcome.t_reached << " s; the rows up to there are written\n";
  } else {
    err << "simulation failed at t = " << outcome.t_reached << " s: " << outcome.failure << "\n";
  }
  PrintStats(sim.stats(), out);
  if (loaded.control) PrintScriptChanges(*loaded.control, *loaded.identifiers, out);
  for (int b = 0; b < loaded.diagram->num_blocks(); ++b) {
    const auto* mechanism = dynamic_cast<const blocks::MechanismBlock*>(&loaded.diagram->block(b));
    if (mechanism && !mechanism->mechanism().constraints().empty())
      out << "mechanism '" << mechanism->name() << "': largest loop-constraint residual before projection "
          << mechanism->worst_constraint_residual(sim.context(), b) << "\n";
  }
  for (const blocks::AlgebraicLoop& loop : loaded.diagram->loops()) {
    const blocks::LoopStats& s = loop.stats(sim.context());
    out << "algebraic loop through " << loop.port() << ": " << s.solves << " solves, "
        << (s.solves ? double(s.iterations) / s.solves : 0.0) << " Newton steps per solve, " << s.jacobians
        << " difference Jacobians, largest accepted residual " << s.worst_residual << "\n";
  }

  // results are written whether or not the run finished
  int plot_stopped_by = 0;  // a signal while gnuplot drew
  bool all_written = WriteRunOutputs(loaded, sim, prepared.columns(), plan, results_file.get(), out, err,
                                     &plot_stopped_by, envelope.get());
  if (folder) all_written = animation.Write(*folder, out, err) && all_written;
  PrintSignalRanges(sim.results(), out);
  PrintFigures(sim.results().figures(), outcome.ok, out);
  if (args.verbose) PrintEventLog(*loaded.diagram, sim.events(), out);
  PrintEventWarnings(*loaded.diagram, sim.events(), err);
  PrintRunWarnings(*loaded.diagram, sim.context(), err);
  // 130 SIGINT, 143 SIGTERM, 129 SIGHUP, as shells report them; after the
  // run, a plot or a <spectrum> stopped by a signal ends the command alike
  const int signal = outcome.interrupted ? outcome.interrupted : plot_stopped_by ? plot_stopped_by : *InterruptFlag();
  if (signal) return 128 + signal;
  return outcome.ok && all_written ? 0 : 1;
}

int CheckCommand(const Arguments& args, std::ostream& out, std::ostream&) {
  const diagrams::LoadedDiagram loaded = diagrams::LoadDiagram(args.file, ToLoadOptions(args));
  PrintCheck(loaded, out);
  const graphics::Scene scene = graphics::BuildScene(loaded);
  if (!scene.empty())
    out << "\ngraphics: " << scene.shapes.size() << " shapes on " << scene.bodies.size() << " moving bodies\n";
  const int unknown = PrintUnknownGlobals(loaded, out) + PrintLoadWarnings(loaded, out);
  out << "\n" << args.file << ": ok" << (unknown ? " (" + std::to_string(unknown) + " warning" + (unknown == 1 ? "" : "s") + ")" : "") << "\n";
  return 0;
}

int GraphCommand(const Arguments& args, std::ostream& out, std::ostream&) {
  const diagrams::LoadedDiagram loaded = diagrams::LoadDiagram(args.file, ToLoadOptions(args));
  PrintDot(loaded, out);
  return 0;
}

int ModesCommand(const Arguments& args, std::ostream& out, std::ostream& err) {
  run::Model model(args.file, ToLoadOptions(args));
  const diagrams::LoadedDiagram& loaded = model.Loaded();
  PrintLoadWarnings(loaded, err);
  const blocks::Diagram& diagram = *loaded.diagram;
  if (diagram.num_states() == 0) {
    err << args.file << ": the diagram has no continuous states; nothing to analyse\n";
    return 2;
  }
  // NAME.modes.csv goes into the output folder, named after the diagram as
  // `run`'s files are: another diagram file's of that name is not overwritten unasked
  const OutputFolder folder(args.out_dir);
  ClaimStems(folder, args.file, {{loaded.description.name, "the diagram's name \"" + loaded.description.name + "\""}},
             args.overwrite, true, out);
  // where: the initial state, or the static equilibrium found from it
  const ModesReport report = analysis::AnalyseModes(diagram, loaded.solver.t_start, args.equilibrium);

  const auto count = [](std::size_t n, const char* what) {
    return std::to_string(n) + " " + what + (n == 1 ? "" : "s");
  };
  out << "mechflow modes " << args.file << ": " << count(report.states.size(), "state") << ", "
      << count(report.modes.size(), "mode") << "\n";
  PrintModes(report, out);

  // written whole (cli/output_folder.h): a full disk is an error naming it (exit 1)
  const std::string name = loaded.description.name + ".modes.csv";
  std::ostringstream csv;
  WriteModesCsv(report.modes, report.states, csv);
  folder.Write(name, csv.str());
  out << "wrote " << folder.PathOf(name) << " (" << count(report.modes.size(), "mode") << ")\n";
  return 0;
}

int Main(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err) {
  Arguments args;
  try {
    args = ParseArguments(argv);
  } catch (const UsageError& e) {
    // the one wrong argument, and the command's own usage lines
    const std::string command = argv.empty() ? "" : argv[0];
    const std::string help = HelpText(command);
    const bool known = help != HelpText("");
    err << "mechflow" << (known ? " " + command : "") << ": " << e.what() << "\n"
        << help.substr(0, help.find("\n\n")) << "\n(mechflow help" << (known ? " " + command : "")
        << " for more)\n";
    return 2;
  }
  if (args.version) {
    out << "mechflow 0.1.0\n";
    return 0;
  }
  if (args.help) {
    out << HelpText(args.command);
    return 0;
  }
  std::ostream null_stream(nullptr);  // --quiet: errors only
  std::ostream& out_or_nothing = args.quiet ? null_stream : out;
  // run --results -: standard output holds the results, the messages go with the errors
  std::ostream& run_messages = args.quiet ? null_stream : args.results == "-" ? err : out;
  try {
    if (args.command == "run") return RunCommand(args, run_messages, err);
    if (args.command == "check") return CheckCommand(args, out, err);
    if (args.command == "graph") return GraphCommand(args, out, err);
    if (args.command == "modes") return ModesCommand(args, out, err);
    if (args.command == "sweep") return SweepCommand(args, out_or_nothing, err);
    if (args.command == "force-analysis") return ForceAnalysisCommand(args, out, err);
    if (args.command == "psd") return PsdCommand(args, out, err);
    if (args.command == "fit") return FitCommand(args, out, err);
    if (args.command == "export-fmu") return ExportFmuCommand(args, out, err);
  } catch (const InputError& e) {
    err << e.what() << "\n";
    return 2;
  } catch (const UsageError& e) {
    err << "mechflow " << args.command << ": " << e.what() << "\n";
    return 2;
  } catch (const SimulationError& e) {
    err << "simulation failed: " << e.what() << "\n";
    return 1;
  } catch (const WriteError& e) {  // a file that could not be written completely (the message names it)
    err << e.what() << "\n";
    return 1;
  } catch (const Interrupted& e) {  // a signal while gnuplot drew: the files before it are written
    err << e.what() << "\n";
    return 128 + e.signal();
  } catch (const std::exception& e) {
    err << "mechflow: internal error: " << e.what() << "\n";
    return 1;
  }
  return 2;
}

}  // namespace mechflow::cli
