#include "cli/sweep.h"

#include "blocks/outputs/csv.h"

#include "cli/plot.h"

#include <unistd.h>

#include <atomic>
#include <charconv>
#include <chrono>
#include <csignal>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "blocks/solver/simulator.h"
#include "blocks/support/suggest.h"
#include "cli/interrupt.h"
#include "cli/output_budget.h"
#include "cli/output_claims.h"
#include "cli/output_folder.h"
#include "cli/plot_envelope.h"
#include "cli/ranks.h"
#include "cli/report.h"
#include "cli/results_file.h"
#include "cli/run_outputs.h"
#include "cli/vary_pattern.h"
#include "diagrams/loader.h"
#include "mech/errors.h"
#include "run/columns.h"
#include "run/model.h"
#include "scripting/instance_path.h"

namespace mechflow::cli {
namespace {

namespace fs = std::filesystem;

// The shortest text that reads back as the same double: "0.05", where %.17g
// would write 0.050000000000000003 into file names and the summary; without
// an exponent in the everyday range (500000, not 5e+05).
std::string Shortest(double v) {
  if (v == 0.0) return "0";  // also -0
  char buffer[64];
  const double a = std::abs(v);
  const bool fixed = a == 0.0 || (a >= 1e-4 && a < 1e15);
  const auto end = fixed ? std::to_chars(buffer, buffer + sizeof buffer, v, std::chars_format::fixed).ptr
                         : std::to_chars(buffer, buffer + sizeof buffer, v).ptr;
  return std::string(buffer, end);
}

// Full precision, as the results and report CSVs write numbers.
std::string Full(double v) { return blocks::CsvNumber(v); }
using blocks::CsvField;

// One line for the summary and the terminal (tracebacks span several).
std::string OneLine(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (c == '\n') out += "; ";
    else if (c != '\r') out += c;
  }
  while (out.size() >= 2 && out.compare(out.size() - 2, 2, "; ") == 0) out.resize(out.size() - 2);
  return out;
}

// Everything a run needs besides its index; read-only while the runs go.
struct Plan {
  std::string file;
  diagrams::DiagramDescription description;  // read once; every worker builds its own model from it
  diagrams::LoadOptions common;            // variants, --set, t_end, unsafe_lua
  std::vector<std::string> names;          // per --vary: its name in the table, file names and labels
  std::vector<std::vector<std::string>> targets;  // per --vary: the identifiers it sets (s[*].mu: several)
  std::vector<std::vector<double>> values; // per varied identifier
  int runs = 1;
  std::shared_ptr<const OutputFolder> folder;  // shared by the threads
  std::string width;                       // digits of the largest run number
  std::vector<std::string> figure_labels;  // the header's figure columns
  std::string csv_file;                    // the diagram's results file name
  std::vector<diagrams::PlotGroup> groups; // logged groups, for the overlay plot
  bool animated = false;                    // <output animation> or <output gltf>: not written by a sweep
  std::vector<std::string> columns;        // the results' column names
  bool event_logs = false;                 // --verbose: each run's event log beside its results
  std::uint64_t max_output = kDefaultMaxOutputBytes;  // bytes per results file (--max-output)
  std::vector<int> plotted;                // the overlay's columns: a long run's envelope follows them
  bool plot = true;                        // the overlay (not with --no-plot), and the envelopes it draws from
  std::string csv_origin;                  // where the results' name comes from, for messages
};

// A run's envelope for the overlay, beside its results.
std::string EnvelopeName(const std::string& results_name) {
  return fs::path(results_name).replace_extension(".envelope.csv").string();
}

// The values of run `index`: mixed radix, the last identifier fastest.
std::vector<double> Combination(const Plan& plan, int index) {
  std::vector<double> v(plan.names.size());
  for (int k = static_cast<int>(plan.names.size()) - 1; k >= 0; --k) {
    const int n = static_cast<int>(plan.values[k].size());
    v[k] = plan.values[k][index % n];
    index /= n;
  }
  return v;
}

// "beta=0.05" or "beta=0.05.mass=2" (file names) with `separator`.
std::string Assignments(const Plan& plan, const std::vector<double>& values, const std::string& separator) {
  std::string s;
  for (std::size_t k = 0; k < values.size(); ++k) s += (k ? separator : "") + plan.names[k] + "=" + Shortest(values[k]);
  return s;
}

// Run `index`'s name in the overlay's legend: "beta=0.0316228, mass=2",
// each value in `texts` (LegendNumbers of its identifier's values).
std::string LegendLabel(const Plan& plan, int index, const std::vector<std::vector<std::string>>& texts) {
  std::string label;
  for (int k = static_cast<int>(plan.names.size()) - 1; k >= 0; --k) {  // mixed radix, as Combination
    const int n = static_cast<int>(plan.values[k].size());
    label = plan.names[k] + "=" + texts[k][index % n] + (label.empty() ? "" : ", " + label);
    index /= n;
  }
  return label;
}

// damping_ratio.csv -> damping_ratio.run02.beta=0.1.csv (folder kept).
std::string RunFileName(const Plan& plan, const std::string& csv_file, int index, const std::vector<double>& values) {
  std::string number = std::to_string(index + 1);
  number.insert(0, plan.width.size() - number.size(), '0');
  const fs::path p(csv_file);
  const std::string name = p.stem().string() + ".run" + number + "." + Assignments(plan, values, ".") +
                           p.extension().string();
  return (p.parent_path() / name).string();
}

// What a run leaves behind: its summary line and its line for the terminal.
struct RunRow {
  bool ok = false;
  std::string csv;      // without the newline
  std::string message;  // "run 2/3 (beta=0.1): ok, t = 10 s"
};

// Run `index` on `model`, this worker's (made at its first run, from the
// description read once; each run rebuilds it with its values: run/model.h).
RunRow RunOne(const Plan& plan, int index, std::unique_ptr<run::Model>* model) {
  const std::vector<double> values = Combination(plan, index);
  if (const int signal = *InterruptFlag()) {  // Ctrl-C before this run began: not run
    RunRow row;
    row.csv = std::to_string(index + 1);
    for (const double v : values) row.csv += "," + Shortest(v);
    row.csv += ",not run,,interrupted,";
    for (std::size_t i = 0; i < plan.figure_labels.size(); ++i) row.csv += ",,";
    row.message = "run " + std::to_string(index + 1) + "/" + std::to_string(plan.runs) + " (" +
                  Assignments(plan, values, ", ") + "): not run (" + SignalName(signal) + ")";
    return row;
  }
  bool ran = false, ok = false, stopped = false;
  double t_reached = 0.0;
  std::string error, results_file;
  std::vector<blocks::ReportFigure> figures;
  try {
    if (!*model) *model = std::make_unique<run::Model>(plan.description, plan.common);
    for (std::size_t k = 0; k < values.size(); ++k)
      for (const std::string& target : plan.targets[k]) (*model)->Set(target, values[k]);
    std::unique_ptr<ResultsFile> file;
    run::RunOptions options;
    options.interrupt = InterruptFlag();
    options.progress = [&](double) {
      if (!file->stopped().empty()) throw SimulationError(file->stopped());  // past the budget: rows kept
    };
    run::PreparedRun prepared = (*model)->Prepare(options);
    const diagrams::LoadedDiagram& loaded = prepared.loaded();
    const blocks::Simulator& sim = prepared.simulator();
    // rows streamed as computed, as `run` does; written whether or not the run finishes
    const std::string name = RunFileName(plan, loaded.csv_file, index, values);
    // its values may lengthen the run: each run is estimated before it starts
    RefuseOverBudget(EstimateResultsCsv(sim.options(), sim.results().num_columns(), name), plan.max_output);
    file = std::make_unique<ResultsFile>(*plan.folder, name, sim.results().columns());
    file->SetByteLimit(plan.max_output);
    PlotEnvelope envelope(plan.plotted, {}, loaded.solver.t_end - loaded.solver.t_start, file.get());
    const run::RunResult result = prepared.Run(&envelope);
    ran = true;
    ok = result.outcome.ok;
    stopped = result.outcome.stopped;
    t_reached = result.t_reached;
    if (!ok) error = result.outcome.failure;
    if (stopped) error = result.outcome.stop_reason;
    figures = result.figures;
    if (const std::string problem = file->Close(); !problem.empty()) throw WriteError(problem);
    results_file = name;
    // a long run's curves in the overlay come from its envelope (and no
    // envelope of an earlier sweep stays to be drawn)
    if (plan.plot && envelope.worthwhile() && !plan.groups.empty())
      plan.folder->Write(EnvelopeName(name), envelope.Csv(sim.results().columns()));
    else plan.folder->Clear(EnvelopeName(name));
    if (plan.event_logs) {
      std::ostringstream log;
      PrintEventLog(*loaded.diagram, result.events, log);
      plan.folder->Write(fs::path(name).replace_extension(".events.txt").string(), log.str());
    }
  } catch (const std::exception& e) {
    ok = false;
    error += (error.empty() ? "" : "; ") + std::string(e.what());
  }
  error = OneLine(error);

  RunRow row;
  row.ok = ok;
  row.csv = std::to_string(index + 1);
  for (const double v : values) row.csv += "," + Shortest(v);
  row.csv += !ok ? ",failed," : stopped ? ",stopped," : ",ok,";
  row.csv += (ran ? Full(t_reached) : "") + "," + CsvField(error) + "," + CsvField(results_file);
  for (std::size_t i = 0; i < plan.figure_labels.size(); ++i) {
    const bool found = i < figures.size() && figures[i].found;
    row.csv += "," + (found ? Full(figures[i].value) : "") + "," + (found ? Full(figures[i].time) : "");
  }

  row.message = "run " + std::to_string(index + 1) + "/" + std::to_string(plan.runs) + " (" +
                Assignments(plan, values, ", ") + "): ";
  if (ok && stopped) row.message += "stopped by the control script at t = " + Shortest(t_reached) + " s: " + error;
  else if (ok) row.message += "ok, t = " + Shortest(t_reached) + " s";
  else if (ran) row.message += "failed at t = " + Shortest(t_reached) + " s: " + error;
  else row.message += "failed: " + error;
  return row;
}

std::string SummaryHeader(const Plan& plan, const diagrams::LoadedDiagram& base);

// The checks before anything runs; every rank makes them alike, so all stop
// together. Also the summary's header and file name. Throws InputError.
Plan MakePlan(const Arguments& args, std::string* header, std::string* summary_name) {
  Plan plan;
  plan.file = args.file;
  plan.common.variants = args.variants;
  plan.common.overrides = args.overrides;
  plan.common.expression_overrides = args.set_expressions;
  plan.event_logs = args.verbose;
  plan.max_output = args.max_output_bytes.value_or(kDefaultMaxOutputBytes);
  plan.common.t_end = args.t_end;
  plan.common.rtol = args.rtol;
  plan.common.atol = args.atol;
  plan.common.interval = args.interval;
  plan.common.results = args.results;
  plan.common.unsafe_lua = args.unsafe_lua;
  plan.common.allow_read = args.allow_read;
  plan.common.library = args.library;

  // the diagram must load as given; its identifiers judge the --vary names
  run::Model model(args.file, plan.common);
  const diagrams::LoadedDiagram& base = model.Loaded();
  plan.description = model.description();
  const scripting::IdentifierTable& ids = *base.identifiers;
  for (const auto& [name, values] : args.vary) {
    std::vector<int> matched;
    if (IsVaryPattern(name)) {
      matched = MatchVaryPattern(ids, name);
      if (matched.empty()) {
        std::vector<std::string> patterns;
        for (int i = 0; i < ids.size(); ++i) patterns.push_back(AsVaryPattern(ids.spelling(i)));
        throw InputError("--vary " + name + ": " + args.file + " has no identifier '" + name +
                         "' for any index ([*] stands for [0], [1], ...)" + blocks::DidYouMean(name, patterns));
      }
    } else if (const int i = ids.Find(name); i >= 0) {
      matched = {i};
    } else {
      throw InputError("--vary " + name + ": " + args.file + " has no identifier '" + name + "'" +
                       blocks::DidYouMean(name, ids.ShownNames()));
    }
    std::vector<std::string> targets;
    for (const int i : matched) {
      if (ids.is_expression(i))
        throw InputError("--vary " + name + ": identifier '" + ids.spelling(i) + "' (" + ids.origin(i) +
                         ") is derived (= " + scripting::WithInstancePaths(ids.definition(i)) +
                         "); it follows the identifiers it uses, vary one of those");
      for (const auto& earlier : plan.targets)
        for (const std::string& seen : earlier)
          if (seen == ids.spelling(i))
            throw InputError("--vary " + name + ": identifier '" + seen + "' is varied twice");
      for (const auto& [set_name, unused] : args.overrides)
        if (ids.Find(set_name) == i)
          throw InputError("--vary " + name + ": identifier '" + ids.spelling(i) + "' is also given by --set");
      targets.push_back(ids.spelling(i));
    }
    // a pattern as the user wrote it; a name as the diagram writes it
    plan.names.push_back(IsVaryPattern(name) ? name : targets.front());
    plan.targets.push_back(std::move(targets));
    plan.values.push_back(values);
  }
  double runs = 1;
  for (const auto& v : plan.values) runs *= static_cast<double>(v.size());
  if (runs > 1e6) throw InputError("--vary: " + Shortest(runs) + " combinations; at most 1000000 runs per sweep");
  plan.runs = static_cast<int>(runs);
  plan.width = std::to_string(plan.runs);
  for (const blocks::ReportRequest& r : base.reports) plan.figure_labels.push_back(r.label);
  plan.csv_file = base.csv_file;
  plan.csv_origin = ResultsNameOrigin(base, args.results);
  plan.plot = !args.no_plot;
  plan.animated = !base.animation_file.empty() || !base.gltf_file.empty();
  plan.groups = base.groups;
  plan.plotted = PlottedColumns(base.groups);
  plan.columns = run::ColumnNames(base.logged);
  *header = SummaryHeader(plan, base);
  // each run's results, at the diagram's own values, within the budget
  // (runs whose values lengthen them are checked again as they start)
  RefuseOverBudget(EstimateResultsCsv(base.solver, static_cast<int>(plan.columns.size()),
                                      RunFileName(plan, plan.csv_file, 0, Combination(plan, 0))),
                   plan.max_output);
  const fs::path csv(base.csv_file);
  *summary_name = (csv.parent_path() / (csv.stem().string() + ".sweep.csv")).string();
  return plan;
}

std::string SummaryHeader(const Plan& plan, const diagrams::LoadedDiagram& base) {
  std::string h = "run";
  for (const std::string& name : plan.names) h += "," + CsvField(name);
  h += ",status,t_reached,error,results";
  for (const blocks::ReportRequest& r : base.reports) {
    h += "," + CsvField(run::WithUnit(r.label, r.unit));
    h += "," + CsvField(run::WithUnit(r.label + " time", "s"));
  }
  return h;
}

// Runs done so far, on one line of a terminal (rank 0's own runs under MPI):
// shown after a second, refreshed at most ten times a second, erased at the end.
class SweepProgress {
 public:
  SweepProgress(int runs, bool enabled) : runs_(runs), enabled_(enabled && isatty(STDERR_FILENO)) {}
  ~SweepProgress() {
    if (shown_) std::fprintf(stderr, "\r%*s\r", 70, "");
  }
  void Done(bool failed) {
    if (!enabled_) return;
    const std::lock_guard<std::mutex> lock(mutex_);
    ++done_;
    failed_ += failed;
    const auto now = Clock::now();
    if (now - start_ < std::chrono::seconds(1) || (shown_ && now - last_ < std::chrono::milliseconds(100))) return;
    last_ = now;
    shown_ = true;
    std::fprintf(stderr, "\r  sweep: %d/%d runs done, %d failed, %8.1f s elapsed ", done_, runs_, failed_,
                 std::chrono::duration<double>(now - start_).count());
  }

 private:
  using Clock = std::chrono::steady_clock;
  std::mutex mutex_;
  int runs_, done_ = 0, failed_ = 0;
  bool enabled_, shown_ = false;
  Clock::time_point start_ = Clock::now(), last_ = start_;
};

// A rank's rows for rank 0: "index\0ok\0csv\0message\0" each.
std::string Pack(const std::vector<int>& indices, const std::vector<RunRow>& rows) {
  std::string s;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    s += std::to_string(indices[k]) + '\0' + (rows[k].ok ? "1" : "0") + '\0' + rows[k].csv + '\0' +
         rows[k].message + '\0';
  }
  return s;
}

void Unpack(const std::string& s, std::vector<RunRow>* all) {
  std::vector<std::string> fields;
  for (std::size_t start = 0; start < s.size();) {
    const std::size_t end = s.find('\0', start);
    fields.push_back(s.substr(start, end - start));
    start = end + 1;
  }
  for (std::size_t f = 0; f + 3 < fields.size(); f += 4) {
    RunRow& row = all->at(std::stoul(fields[f]));
    row.ok = fields[f + 1] == "1";
    row.csv = fields[f + 2];
    row.message = fields[f + 3];
  }
}

}  // namespace

std::vector<std::thread> StartThreads(int wanted, const std::function<void()>& worker, const ThreadStarter& start) {
  std::vector<std::thread> threads;
  threads.reserve(static_cast<std::size_t>(std::max(0, wanted)));  // no reallocation below: push_back cannot throw
  for (int j = 0; j < wanted; ++j) {
    try {
      threads.push_back(start(worker));
    } catch (const std::exception&) {  // std::system_error (EAGAIN), or no memory for the thread's state
      break;
    }
  }
  return threads;
}

int SweepCommand(const Arguments& args, std::ostream& out, std::ostream& err) {
  std::unique_ptr<Ranks> ranks;
  try {
    ranks = std::make_unique<Ranks>();
  } catch (const std::exception& e) {
    err << "mechflow sweep: " << e.what() << "\n";
    return 2;
  }
  Plan plan;
  std::string header, summary_name;
  try {
    plan = MakePlan(args, &header, &summary_name);
  } catch (const InputError& e) {
    if (ranks->root()) err << e.what() << "\n";
    return 2;
  }
  try {
    plan.folder = std::make_shared<const OutputFolder>(args.out_dir);
  } catch (const InputError& e) {
    if (ranks->root()) err << e.what() << "\n";
    return 2;
  }
  // another diagram file's results there are not overwritten unasked: every
  // process checks, process 0 records; all stop if one refuses
  std::string refused;
  std::ostream null_stream(nullptr);
  try {
    ClaimStems(*plan.folder, args.file, {{StemOf(plan.csv_file), plan.csv_origin}}, args.overwrite, ranks->root(),
               ranks->root() ? out : null_stream);
  } catch (const std::runtime_error& e) {  // InputError; WriteError from the record
    refused = e.what();
  }
  if (ranks->Max(refused.empty() ? 0 : 1) > 0) {
    if (ranks->root())
      err << (refused.empty() ? "mechflow sweep: another MPI process could not check " +
                                    plan.folder->PathOf(kOutputRecordName) + "; nothing was run"
                              : refused)
          << "\n";
    return 2;
  }

  // this rank's runs, dealt in turn; threads take them in order
  std::vector<int> mine;
  for (int i = ranks->rank(); i < plan.runs; i += ranks->size()) mine.push_back(i);
  const int cores = std::max(1u, std::thread::hardware_concurrency());
  const int jobs = std::max(1, std::min<int>(args.jobs.value_or(std::max(1, cores / ranks->local_size())),
                                             static_cast<int>(mine.size())));
  const auto wall_start = std::chrono::steady_clock::now();
  std::vector<RunRow> rows(mine.size());
  const InterruptHandlers handlers;  // Ctrl-C, SIGTERM: the runs under way end, the rest are not run
  {
    SweepProgress progress(static_cast<int>(mine.size()), ranks->root());
    std::atomic<std::size_t> next{0};
    auto worker = [&] {
      std::unique_ptr<run::Model> model;  // this thread's
      for (std::size_t k = next++; k < mine.size(); k = next++) {
        rows[k] = RunOne(plan, mine[k], &model);
        progress.Done(!rows[k].ok);
      }
    };
    // this thread is one of the jobs; the threads it could start are the others
    std::vector<std::thread> threads =
        StartThreads(jobs - 1, worker, [](const std::function<void()>& w) { return std::thread(w); });
    const int running = 1 + static_cast<int>(threads.size());
    if (running < jobs)
      err << "mechflow: could start only " << running << " of " << jobs << " threads; running with " << running
          << "\n" << std::flush;
    if (ranks->root())
      out << "mechflow sweep " << args.file << ": " << plan.runs << " run" << (plan.runs == 1 ? "" : "s") << ", "
          << running << " at a time"
          << (ranks->size() > 1 ? " in each of " + std::to_string(ranks->size()) + " processes" : "") << "\n"
          << (plan.animated ? "note: a sweep writes no animation; animate one case with `mechflow run " + args.file +
                                  " --set NAME=VALUE`\n"
                            : "")
          << std::flush;
    worker();
    for (std::thread& t : threads) t.join();
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();

  const int interrupted = *InterruptFlag();
  int failed_here = 0;
  for (const RunRow& row : rows) failed_here += !row.ok;
  const std::vector<std::string> parts = ranks->GatherToRoot(Pack(mine, rows));
  const bool any_failed = ranks->Max(failed_here > 0 ? 1 : 0) > 0;
  if (!ranks->root()) return interrupted ? 128 + interrupted : any_failed ? 1 : 0;

  std::vector<RunRow> all(plan.runs);
  for (const std::string& part : parts) Unpack(part, &all);
  int failed = 0;
  for (const RunRow& row : all) {
    failed += !row.ok;
    (row.ok ? out : err) << row.message << "\n";
  }
  std::ostringstream summary;
  summary << header << "\n";
  for (const RunRow& row : all) summary << row.csv << "\n";
  out << "finished in " << wall << " s of wall time: " << plan.runs - failed << " ok, " << failed << " failed\n";
  try {
    plan.folder->Write(summary_name, summary.str());
  } catch (const WriteError& e) {
    err << e.what() << "\n";
    return 1;
  }
  out << "wrote " << plan.folder->PathOf(summary_name) << " (" << plan.runs << " run" << (plan.runs == 1 ? "" : "s")
      << ")\n";
  // every run's curves over one another, a panel per logged group. A signal
  // from here on (the summary is written) leaves the overlay out; one during
  // the runs does not: the overlay shows the runs done, as `run` plots its rows
  const auto stopped_now = [&] { return interrupted == 0 && *InterruptFlag() != 0; };
  std::vector<OverlayRun> overlay;
  std::vector<std::vector<std::string>> legend_numbers;
  for (const std::vector<double>& values : plan.values) legend_numbers.push_back(LegendNumbers(values));
  for (int i = 0; plan.plot && i < plan.runs && !stopped_now(); ++i) {
    const std::vector<double> values = Combination(plan, i);
    const std::string name = RunFileName(plan, plan.csv_file, i, values);
    if (plan.folder->HasFile(name))
      overlay.push_back({name, LegendLabel(plan, i, legend_numbers),
                         plan.folder->HasFile(EnvelopeName(name)) ? EnvelopeName(name) : ""});
  }
  const std::string plot = fs::path(summary_name).replace_extension(".png").string();
  const auto signal_name = [] { return *InterruptFlag() == SIGTERM ? "SIGTERM" : "SIGINT"; };
  if (!plan.plot) {
    // --no-plot: gnuplot draws nothing
  } else if (stopped_now()) {
    err << "warning: no plot: interrupted by " << signal_name() << "\n";
  } else {
    try {
      const std::string warning = DrawPlot(
          OverlayScript(plan.groups, plan.columns, overlay, fs::path(plan.csv_file).stem().string() + " sweep", plot),
          *plan.folder, plot);
      if (warning.empty()) out << "wrote " << plan.folder->PathOf(plot) << " (every run over one another)\n";
      else err << "warning: no plot: " << warning << "\n";
    } catch (const WriteError& e) {
      // a Ctrl-C at the terminal reaches gnuplot too (same process group) and ends it: not a write failure
      if (!*InterruptFlag()) {
        err << e.what() << "\n";
        return 1;
      }
      err << "warning: no plot: interrupted by " << signal_name() << "\n";
    }
  }
  if (const int signal = *InterruptFlag()) return 128 + signal;  // 130 SIGINT, 143 SIGTERM
  return failed > 0 ? 1 : 0;
}

}  // namespace mechflow::cli
