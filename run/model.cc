#include "run/model.h"

#include <algorithm>
#include <cctype>
#include <chrono>

#include "blocks/support/suggest.h"
#include "diagrams/output_requests.h"
#include "diagrams/xml_reader.h"
#include "mech/errors.h"
#include "scripting/instance_path.h"

namespace mechflow::run {
namespace {

// A later Set of identifier i replaces the earlier one, a number or an
// expression: `value` goes into `own` (in place, or appended as `name`) and
// any entry of i leaves `other`.
template <typename Value, typename Other>
void Override(const scripting::IdentifierTable& ids, int i, const std::string& name, const Value& value,
              std::vector<std::pair<std::string, Value>>* own, Other* other) {
  std::erase_if(*other, [&](const auto& o) { return ids.Find(o.first) == i; });
  const auto same = std::find_if(own->begin(), own->end(), [&](const auto& o) { return ids.Find(o.first) == i; });
  if (same != own->end()) same->second = value;
  else own->emplace_back(name, value);
}

// Every field of diagrams::LoadOptions (a field added there belongs here too).
// Whether a built diagram may serve another run: its runs keep their states,
// signals and caches in their own blocks::Context (as parallel runs on one
// diagram do), so only a control script (sim:set), a Lua block or an
// expression that calls more than pure functions of numbers could carry
// something from one run into the next.
bool Rerunnable(const diagrams::LoadedDiagram& loaded) {
  return !loaded.control && !(loaded.lua && loaded.lua->has_code_that_may_keep_state());
}

}  // namespace

// `options` is copied, not moved: the order in which the two arguments are
// made is unspecified, and the read needs its folders
Model::Model(const std::string& path, LoadOptions options)
    : Model(diagrams::ReadDiagramFile(path, options.allow_read, options.library), options) {}

Model::Model(diagrams::DiagramDescription description, LoadOptions options)
    : description_(std::move(description)), options_(std::move(options)) {
  Build(options_);
}

void Model::Build(const LoadOptions& options) {
  // the old build stays when the new one is refused (a Set value its model refuses)
  loaded_ = std::make_unique<diagrams::LoadedDiagram>(diagrams::LoadDiagramDescription(description_, options));
  built_with_ = options;
  built_from_ = options_;
  used_ = false;
}

const diagrams::LoadedDiagram& Model::Loaded() {
  if (options_ != built_from_) Build(options_);
  return *loaded_;
}

std::vector<Identifier> Model::Identifiers() {
  const scripting::IdentifierTable& ids = *Loaded().identifiers;
  std::vector<Identifier> out;
  for (int i = 0; i < ids.size(); ++i)
    out.push_back({ids.spelling(i), ids.value(i), ids.unit(i), ids.comment(i), ids.is_expression(i)});
  return out;
}

std::vector<std::string> Model::LoggableSignals() {
  const blocks::Diagram& diagram = *Loaded().diagram;
  std::vector<std::string> out;
  for (int b = 0; b < diagram.num_blocks(); ++b)
    for (int p = 0; p < diagram.block(b).num_outputs(); ++p)
      out.push_back(diagram.block(b).name() + "." + diagram.block(b).output_port(p).name);
  return out;
}

// Refused as --set refuses them (the same words), before any rebuild.
int Model::FindIdentifier(const std::string& name) {
  const scripting::IdentifierTable& ids = *loaded_->identifiers;  // names do not change with values
  const int i = ids.Find(name);
  if (i < 0) {
    std::string lower = name;
    for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    const std::vector<std::string> names = ids.ShownNames();
    throw InputError("--set " + name + ": no identifier named '" + name + "'" + blocks::DidYouMean(lower, names) +
                     (ids.size() == 0 ? "; the diagram defines none" : "; identifiers: " + blocks::JoinNames(names)));
  }
  if (ids.is_expression(i)) {
    const std::string shown = scripting::WithInstancePaths(ids.name(i));
    throw InputError("--set " + name + ": identifier '" + shown + "' is defined by an expression (" + shown + " = " +
                     scripting::WithInstancePaths(ids.definition(i)) + ", at " + ids.origin(i) +
                     "); set the identifiers it depends on instead");
  }
  return i;
}

void Model::Set(const std::string& name, double value) {
  const int i = FindIdentifier(name);
  Override(*loaded_->identifiers, i, name, value, &options_.overrides, &options_.expression_overrides);
}

void Model::SetExpression(const std::string& name, const std::string& expression) {
  const int i = FindIdentifier(name);
  Override(*loaded_->identifiers, i, name, expression, &options_.expression_overrides, &options_.overrides);
}

LoadOptions Model::Effective(const RunOptions& options) const {
  LoadOptions o = options_;
  if (options.t_end) o.t_end = options.t_end;
  if (options.rtol) o.rtol = options.rtol;
  if (options.atol) o.atol = options.atol;
  if (options.interval) o.interval = options.interval;
  return o;
}

PreparedRun Model::Prepare(const RunOptions& options) {
  if (!options.times.empty() && options.interval)
    throw InputError("run: output at given times and an output interval exclude each other; give one");
  const LoadOptions effective = Effective(options);
  if ((used_ && !Rerunnable(*loaded_)) || effective != built_with_) Build(effective);
  used_ = true;
  return PreparedRun(*loaded_, options);
}

RunResult Model::Run(const RunOptions& options, blocks::RowSink* sink) { return Prepare(options).Run(sink); }

PreparedRun::PreparedRun(const diagrams::LoadedDiagram& loaded, const RunOptions& options)
    : loaded_(&loaded), options_(options) {
  std::vector<blocks::SignalRef> logged = loaded.logged;
  std::vector<std::string> units = loaded.units;
  if (options.log) {
    logged.clear();
    units = {"s"};
    for (const std::string& name : *options.log) {
      try {
        logged.push_back(loaded.diagram->ResolveSignal(name));
      } catch (const InputError& e) {
        throw InputError("log " + name + ": " + e.what());
      }
      units.resize(units.size() + logged.back().width, diagrams::RawSignalUnit(loaded, logged.back()));
    }
  }
  blocks::SolverOptions solver = loaded.solver;
  solver.output_times = options.times;
  const std::string problem = solver.OutputTimesProblem();
  if (!problem.empty()) throw InputError("run: " + problem);
  sim_ = std::make_unique<blocks::Simulator>(*loaded.diagram, solver, logged);
  sim_->SetReports(loaded.reports);
  sim_->SetControl(loaded.control.get());
  sim_->SetInterruptFlag(options.interrupt);
  const std::vector<std::string> names = ColumnNames(logged);
  for (std::size_t c = 0; c < names.size(); ++c) columns_.push_back({names[c], units[c]});
}

RunResult PreparedRun::Run(blocks::RowSink* sink) {
  if (ran_) throw std::logic_error("run::PreparedRun::Run: a prepared run runs once");
  ran_ = true;
  std::vector<int> keep;
  for (const std::string& name : options_.keep) {
    const int c = sim_->results().FindColumn(name);
    if (c < 0)
      throw InputError("keep " + name + ": not a column of the run" +
                       blocks::DidYouMean(name, sim_->results().columns()));
    keep.push_back(c);
  }
  sim_->StreamRows(sink, keep);
  RunResult r;
  const auto start = std::chrono::steady_clock::now();
  r.outcome = sim_->Run(options_.progress);
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.t_reached = r.outcome.t_reached;
  r.signal = r.outcome.interrupted;
  if (r.outcome.stopped) {
    r.status = Status::kStopped;
    r.reason = r.outcome.stop_reason;
  } else if (!r.outcome.ok) {
    r.status = r.signal ? Status::kInterrupted : Status::kFailed;
    r.reason = r.outcome.failure;
  }
  r.stats = sim_->stats();
  r.events = sim_->events();
  r.figures = sim_->results().figures();
  r.columns = columns_;
  r.rows = sim_->results().num_rows();
  return r;
}

}  // namespace mechflow::run
