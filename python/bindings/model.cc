// mechflow.load's object: a diagram read once, run as often as wanted, alone
// or many at a time on C++ threads (run/model.h).

#include <atomic>
#include <exception>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include "analysis/interrupted.h"
#include "analysis/modes.h"
#include "blocks/outputs/report.h"
#include "diagrams/xml_reader.h"
#include "mech/errors.h"
#include "python/bindings/bindings.h"
#include "run/model.h"
#include "run/sinks.h"

namespace mechflow::python {
namespace {

// One run's request, read from its Python keywords while the GIL is held.
struct RunRequest {
  Settings settings;
  std::optional<double> t_end, rtol, atol, interval;
  std::optional<std::vector<std::string>> log;
  std::vector<double> times;
};

// One run's outcome, made without the GIL; turned into Python after.
struct RunRecord {
  bool ran = false;              // false: refused before it ran (error_kind says why)
  run::RunResult result;
  std::vector<std::vector<double>> data;  // the rows, a vector per column (time first)
  std::vector<std::string> event_names;   // per event: "block: crossing" as the event log names it
  std::string error_kind;        // "" none; "DiagramError", "SimulationError", "Error", "Interrupted"
  std::string error;             // its message
};

template <typename T>
std::optional<T> Optional(const py::dict& d, const char* key) {
  if (!d.contains(key) || d[key].is_none()) return std::nullopt;
  return d[key].cast<T>();
}

RunRequest ToRequest(const py::dict& kwargs) {
  static const char* kKeys[] = {"set", "t_end", "rtol", "atol", "interval", "log", "times"};
  for (const auto& [key, value] : kwargs) {
    const std::string k = py::str(key);
    bool known = false;
    for (const char* allowed : kKeys) known = known || k == allowed;
    if (!known)
      throw py::type_error("run: unknown keyword '" + k + "' (set, t_end, rtol, atol, interval, log, times)");
  }
  RunRequest r;
  if (kwargs.contains("set")) r.settings = ToSettings(kwargs["set"]);
  r.t_end = Optional<double>(kwargs, "t_end");
  r.rtol = Optional<double>(kwargs, "rtol");
  r.atol = Optional<double>(kwargs, "atol");
  r.interval = Optional<double>(kwargs, "interval");
  if (kwargs.contains("log") && !kwargs["log"].is_none()) {
    if (py::isinstance<py::str>(kwargs["log"])) r.log = std::vector<std::string>{kwargs["log"].cast<std::string>()};
    else r.log = kwargs["log"].cast<std::vector<std::string>>();
  }
  if (kwargs.contains("times") && !kwargs["times"].is_none()) r.times = kwargs["times"].cast<std::vector<double>>();
  return r;
}

std::string CrossingName(const blocks::Diagram& diagram, const blocks::EventRecord& e) {
  const blocks::Block& block = diagram.block(e.block);
  const std::string name = block.CrossingName(e.crossing, e.direction);
  if (!name.empty()) return block.name() + (block.type() == "mechanism" ? "." : ": ") + name;
  return "block '" + block.name() + "' zero crossing " + std::to_string(e.crossing) +
         (e.direction > 0 ? " rising" : e.direction < 0 ? " falling" : "");
}

// The run::Model a thread's runs with the same settings share: it runs its
// built diagram again when it can (run/model.h), which saves the build (a
// quarter of a short run).
struct ModelCache {
  std::unique_ptr<run::Model> model;
  diagrams::LoadOptions options;

  run::Model& For(const diagrams::DiagramDescription& description, const diagrams::LoadOptions& wanted) {
    if (!model || wanted != options) {
      model.reset();  // a model that fails to build is not kept
      model = std::make_unique<run::Model>(description, wanted);
      options = wanted;
    }
    return *model;
  }
};

// A run on the cache's model, built from the description with the base
// options and the run's settings as `mechflow run --set ...` builds it, so
// the rows are the command line's bit for bit. Never throws: what goes wrong
// is recorded.
RunRecord RunOne(const diagrams::DiagramDescription& description, const diagrams::LoadOptions& base,
                 const RunRequest& request, const volatile std::sig_atomic_t* interrupt, ModelCache* cache) {
  RunRecord record;
  try {
    if (interrupt && *interrupt) throw analysis::Interrupted(*interrupt);
    diagrams::LoadOptions options = WithSettings(base, request.settings);
    options.t_end = request.t_end ? request.t_end : base.t_end;
    options.rtol = request.rtol ? request.rtol : base.rtol;
    options.atol = request.atol ? request.atol : base.atol;
    options.interval = request.interval ? request.interval : base.interval;
    run::Model& model = cache->For(description, options);
    run::RunOptions run_options;
    run_options.log = request.log;
    run_options.times = request.times;
    // the overrides again, as the run's own: the model is built with them
    // already (no second build), and Prepare refuses times with an interval
    run_options.t_end = request.t_end;
    run_options.rtol = request.rtol;
    run_options.atol = request.atol;
    run_options.interval = request.interval;
    run_options.interrupt = interrupt;
    run::MemorySink sink;
    run::PreparedRun prepared = model.Prepare(run_options);
    record.result = prepared.Run(&sink);
    record.ran = true;
    record.data = sink.TakeColumns();
    record.data.resize(record.result.columns.size());  // no rows: empty columns
    for (const blocks::EventRecord& e : record.result.events)
      record.event_names.push_back(CrossingName(*prepared.loaded().diagram, e));
  } catch (const InputError& e) {
    record.error_kind = "DiagramError";
    record.error = e.what();
  } catch (const SimulationError& e) {
    record.error_kind = "SimulationError";
    record.error = e.what();
  } catch (const analysis::Interrupted& e) {
    record.error_kind = "Interrupted";
    record.error = std::string("not run: ") + e.what();
  } catch (const std::exception& e) {
    record.error_kind = "Error";
    record.error = e.what();
  }
  if (!record.ran) cache->model.reset();  // whatever failed, the next run starts from a fresh model
  return record;
}

const char* StatusName(run::Status s) {
  switch (s) {
    case run::Status::kOk: return "ok";
    case run::Status::kStopped: return "stopped";
    case run::Status::kFailed: return "failed";
    case run::Status::kInterrupted: return "interrupted";
  }
  return "";
}

const char* KindName(blocks::ReportKind k) {
  switch (k) {
    case blocks::ReportKind::kPeak: return "peak";
    case blocks::ReportKind::kMin: return "min";
    case blocks::ReportKind::kPeakAbs: return "peak_abs";
    case blocks::ReportKind::kMean: return "mean";
    case blocks::ReportKind::kRms: return "rms";
    case blocks::ReportKind::kIntegral: return "integral";
    case blocks::ReportKind::kFinal: return "final";
    case blocks::ReportKind::kCrossing: return "crossing";
    case blocks::ReportKind::kPeriod: return "period";
  }
  return "";
}

py::dict StatsToPython(const blocks::SolverStats& s) {
  py::dict d;
  d["steps"] = s.steps;
  d["rhs_evaluations"] = s.rhs_evals;
  d["jacobian_rhs_evaluations"] = s.jac_rhs_evals;
  d["jacobians"] = s.jac_evals;
  d["newton_iterations"] = s.newton_iters;
  d["linear_iterations"] = s.linear_iters;
  d["newton_failures"] = s.newton_failures;
  d["error_test_failures"] = s.error_test_failures;
  d["root_evaluations"] = s.root_evals;
  d["events"] = s.events;
  d["sample_hits"] = s.sample_hits;
  d["reinits"] = s.reinits;
  d["restarts"] = s.restarts;
  d["projections"] = s.projections;
  d["projection_failures"] = s.projection_failures;
  d["sparse"] = s.sparse;
  d["krylov"] = s.krylov;
  d["analytic_jacobian"] = s.analytic_jacobian;
  d["newton_size"] = s.newton_size;
  d["colours"] = s.colours;
  d["nonzeros"] = s.nonzeros;
  return d;
}

// The record as the package's Result takes it (python/mechflow/_result.py).
py::dict ToPython(RunRecord&& record) {
  py::dict d;
  d["ran"] = record.ran;
  d["error_kind"] = record.error_kind.empty() ? py::object(py::none()) : py::str(record.error_kind);
  d["error"] = record.error;
  const run::RunResult& r = record.result;
  d["status"] = record.ran ? StatusName(r.status) : record.error_kind == "Interrupted" ? "interrupted" : "failed";
  d["t_reached"] = record.ran ? py::object(py::float_(r.t_reached)) : py::object(py::none());
  d["reason"] = record.ran ? r.reason : record.error;
  d["signal"] = r.signal;
  py::list names, units, data;
  for (std::size_t c = 0; c < r.columns.size(); ++c) {
    names.append(r.columns[c].name);
    units.append(r.columns[c].unit);
    data.append(ToArray(std::move(record.data[c])));
  }
  d["columns"] = names;
  d["units"] = units;
  d["data"] = data;
  py::dict stats = StatsToPython(r.stats);
  stats["wall_seconds"] = r.wall_seconds;  // the simulation alone, without building or handing rows over
  d["stats"] = stats;
  py::list events;
  for (std::size_t i = 0; i < r.events.size(); ++i) {
    py::dict e;
    e["time"] = r.events[i].time;
    e["block"] = r.events[i].block;
    e["crossing"] = r.events[i].crossing;
    e["direction"] = r.events[i].direction;
    e["name"] = record.event_names[i];
    events.append(e);
  }
  d["events"] = events;
  py::list figures;
  for (const blocks::ReportFigure& f : r.figures) {
    py::dict e;
    e["label"] = f.label;
    e["kind"] = KindName(f.kind);
    e["signal"] = f.signal;
    e["found"] = f.found;
    e["value"] = f.value;
    e["unit"] = f.unit;
    e["time"] = f.time;
    figures.append(e);
  }
  d["figures"] = figures;
  return d;
}

// The object behind mechflow.Diagram: the description read once, the load
// options (the sandbox and limits as the command line's), a model built
// from them for what is asked of the diagram itself.
class PyModel {
 public:
  PyModel(const std::string& path, const std::vector<std::string>& variants, const py::object& set,
          const std::vector<std::string>& library, const std::vector<std::string>& allow_read, bool unsafe_lua) {
    base_.variants = variants;
    const Settings s = ToSettings(set);
    base_.overrides = s.numbers;
    base_.expression_overrides = s.expressions;
    base_.library = library;
    base_.allow_read = allow_read;
    base_.unsafe_lua = unsafe_lua;
    path_ = path;
    model_ = std::make_unique<run::Model>(path, base_);
  }

  const std::string& path() const { return path_; }
  std::string name() { return model_->Loaded().description.name; }
  std::string comment() { return model_->Loaded().description.comment; }

  py::list Identifiers() {
    const scripting::IdentifierTable& ids = *model_->Loaded().identifiers;
    py::list out;
    for (int i = 0; i < ids.size(); ++i)
      out.append(py::make_tuple(ids.spelling(i), ids.value(i) / ids.to_si(i), ids.unit(i), ids.comment(i),
                                ids.is_expression(i), ids.value(i)));
    return out;
  }

  std::vector<std::string> Signals() { return model_->LoggableSignals(); }
  std::vector<std::string> Warnings() { return model_->Loaded().warnings; }
  py::dict Check() { return CheckToPython(model_->Loaded()); }

  py::dict Run(const py::dict& kwargs, bool handle_sigint) {
    const RunRequest request = ToRequest(kwargs);
    RunRecord record;
    {
      const py::gil_scoped_release unlocked;
      const SigintGuard guard(handle_sigint);
      // a run on another Python thread uses the shared cache: this one builds its own
      std::unique_lock<std::mutex> mine(cache_mutex_, std::try_to_lock);
      ModelCache spare;
      record = RunOne(model_->description(), base_, request, guard.flag(), mine.owns_lock() ? &cache_ : &spare);
    }
    return ToPython(std::move(record));
  }

  // Runs in input order of their results; `threads` workers take the next
  // run as they finish one. Ctrl-C: the runs under way end at their last
  // row, the others are not run.
  py::list RunMany(const py::list& requests, int threads, bool handle_sigint) {
    std::vector<RunRequest> todo;
    for (const py::handle& r : requests) {
      if (!py::isinstance<py::dict>(r)) throw py::type_error("run_many takes a list of dicts of run() keywords");
      todo.push_back(ToRequest(py::reinterpret_borrow<py::dict>(r)));
    }
    if (threads < 1) throw py::value_error("run_many: threads must be at least 1");
    std::vector<RunRecord> records(todo.size());
    {
      const py::gil_scoped_release unlocked;
      const SigintGuard guard(handle_sigint);
      std::atomic<std::size_t> next{0};
      const auto work = [&] {
        ModelCache cache;  // this thread's
        for (std::size_t i = next++; i < todo.size(); i = next++)
          records[i] = RunOne(model_->description(), base_, todo[i], guard.flag(), &cache);
      };
      const std::size_t n = std::min<std::size_t>(static_cast<std::size_t>(threads), todo.size());
      std::vector<std::thread> workers;
      for (std::size_t t = 1; t < n; ++t) workers.emplace_back(work);
      work();
      for (std::thread& w : workers) w.join();
    }
    py::list out;
    for (RunRecord& r : records) out.append(ToPython(std::move(r)));
    return out;
  }

  py::dict Modes(bool equilibrium, const py::object& set) {
    const diagrams::LoadOptions options = WithSettings(base_, ToSettings(set));
    analysis::ModesAnalysis a;
    {
      const py::gil_scoped_release unlocked;
      run::Model model(model_->description(), options);  // a fresh build, as `mechflow modes` makes it
      const diagrams::LoadedDiagram& loaded = model.Loaded();
      a = analysis::AnalyseModes(*loaded.diagram, loaded.solver.t_start, equilibrium);
    }
    const std::size_t n = a.modes.size(), states = a.states.size();
    py::array_t<double> frequency(n), natural(n), damping(n), decay(n);
    py::array_t<std::complex<double>> eigenvalues(n);
    py::array_t<double> shapes({states, n});
    py::list kinds;
    auto s = shapes.mutable_unchecked<2>();
    for (std::size_t k = 0; k < n; ++k) {
      const analysis::Mode& m = a.modes[k];
      frequency.mutable_at(k) = m.frequency_hz;
      natural.mutable_at(k) = m.natural_frequency_hz;
      damping.mutable_at(k) = m.damping_ratio;
      decay.mutable_at(k) = m.decay_rate;
      eigenvalues.mutable_at(k) = m.eigenvalue;
      for (std::size_t i = 0; i < states; ++i) s(i, k) = m.shape[i];
      static const char* kKinds[] = {"oscillating", "decaying", "growing", "rigid-body"};
      kinds.append(kKinds[static_cast<int>(m.kind)]);
    }
    py::dict d;
    d["time"] = a.time;
    d["states"] = a.states;
    d["x"] = ToArray(std::move(a.x));
    d["coordinate"] = a.roles.coordinate;
    d["rate"] = a.roles.rate;
    d["frequency"] = frequency;
    d["natural_frequency"] = natural;
    d["damping_ratio"] = damping;
    d["decay_rate"] = decay;
    d["eigenvalues"] = eigenvalues;
    d["shapes"] = shapes;
    d["kinds"] = kinds;
    d["switching"] = a.switching;
    if (a.equilibrium) {
      py::dict e;
      e["iterations"] = a.equilibrium->iterations;
      e["residual"] = a.equilibrium->residual;
      e["rounds"] = a.equilibrium->rounds;
      e["switched"] = a.equilibrium->switched;
      d["equilibrium"] = e;
    } else {
      d["equilibrium"] = py::none();
    }
    return d;
  }

  const diagrams::LoadOptions& base() const { return base_; }

 private:
  std::string path_;
  diagrams::LoadOptions base_;
  std::unique_ptr<run::Model> model_;
  ModelCache cache_;  // run()'s, used by one Python thread at a time
  std::mutex cache_mutex_;
};

}  // namespace

py::dict ForceAnalysisToPython(const std::string& path, const diagrams::LoadOptions& base, const py::dict& kwargs,
                               bool handle_sigint);

void BindModel(py::module_& m) {
  py::class_<PyModel>(m, "Model", "A diagram read once (run::Model); mechflow.Diagram wraps it")
      .def(py::init<const std::string&, const std::vector<std::string>&, const py::object&,
                    const std::vector<std::string>&, const std::vector<std::string>&, bool>(),
           py::arg("path"), py::arg("variants"), py::arg("set"), py::arg("library"), py::arg("allow_read"),
           py::arg("unsafe_lua"), "Reads and builds the file; DiagramError for bad input")
      .def_property_readonly("path", &PyModel::path)
      .def_property_readonly("name", &PyModel::name)
      .def_property_readonly("comment", &PyModel::comment)
      .def("identifiers", &PyModel::Identifiers, "(name, value in unit, unit, comment, derived, SI value) tuples")
      .def("signals", &PyModel::Signals, "Every loggable \"block.port\"")
      .def("warnings", &PyModel::Warnings, "The loader's warnings")
      .def("check", &PyModel::Check, "`mechflow check` as a dict")
      .def("run", &PyModel::Run, py::arg("kwargs"), py::arg("handle_sigint"),
           "One run from run() keywords; a dict of its rows and report")
      .def("run_many", &PyModel::RunMany, py::arg("requests"), py::arg("threads"), py::arg("handle_sigint"),
           "Runs on C++ threads without the GIL; their dicts in input order")
      .def("modes", &PyModel::Modes, py::arg("equilibrium"), py::arg("set"), "`mechflow modes` as a dict of arrays")
      .def(
          "force_analysis",
          [](PyModel& self, const py::dict& kwargs, bool handle_sigint) {
            return ForceAnalysisToPython(self.path(), self.base(), kwargs, handle_sigint);
          },
          py::arg("kwargs"), py::arg("handle_sigint"), "`mechflow force-analysis` as a dict of arrays");
}

}  // namespace mechflow::python
