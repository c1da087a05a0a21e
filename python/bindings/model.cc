// mechflow.load's object: a diagram read once, run as often as wanted, alone
// or many at a time on C++ threads (run/model.h, run/batch.h).

#include <memory>
#include <mutex>
#include <optional>

#include "analysis/modes.h"
#include "blocks/outputs/report.h"
#include "python/bindings/bindings.h"
#include "run/batch.h"
#include "run/model.h"

namespace mechflow::python {
namespace {

template <typename T>
std::optional<T> Optional(const py::dict& d, const char* key) {
  if (!d.contains(key) || d[key].is_none()) return std::nullopt;
  return d[key].cast<T>();
}

// One run's job, read from its Python keywords while the GIL is held.
run::BatchJob ToJob(const py::dict& kwargs) {
  static const char* kKeys[] = {"set", "t_end", "rtol", "atol", "interval", "log", "times"};
  for (const auto& [key, value] : kwargs) {
    const std::string k = py::str(key);
    bool known = false;
    for (const char* allowed : kKeys) known = known || k == allowed;
    if (!known)
      throw py::type_error("run: unknown keyword '" + k + "' (set, t_end, rtol, atol, interval, log, times)");
  }
  run::BatchJob job;
  if (kwargs.contains("set")) {
    Settings settings = ToSettings(kwargs["set"]);
    job.set = std::move(settings.numbers);
    job.set_expressions = std::move(settings.expressions);
  }
  job.options.t_end = Optional<double>(kwargs, "t_end");
  job.options.rtol = Optional<double>(kwargs, "rtol");
  job.options.atol = Optional<double>(kwargs, "atol");
  job.options.interval = Optional<double>(kwargs, "interval");
  if (kwargs.contains("log") && !kwargs["log"].is_none())  // a list (the package makes one of a name)
    job.options.log = kwargs["log"].cast<std::vector<std::string>>();
  if (kwargs.contains("times") && !kwargs["times"].is_none())
    job.options.times = kwargs["times"].cast<std::vector<double>>();
  return job;
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

const char* RefusalName(run::Refusal r) {
  switch (r) {
    case run::Refusal::kNone: return nullptr;
    case run::Refusal::kInput: return "DiagramError";
    case run::Refusal::kSimulation: return "SimulationError";
    case run::Refusal::kInterrupted: return "Interrupted";
    case run::Refusal::kOther: return "Error";
  }
  return "Error";
}

// The outcome as the package's Result takes it (python/mechflow/_result.py).
py::dict ToPython(run::BatchOutcome&& outcome) {
  py::dict d;
  const run::RunResult& r = outcome.result;
  const bool ran = outcome.refused == run::Refusal::kNone;
  d["ran"] = ran;
  d["error_kind"] = ran ? py::object(py::none()) : py::str(RefusalName(outcome.refused));
  d["error"] = ran ? std::string() : r.reason;
  d["status"] = StatusName(r.status);
  d["t_reached"] = ran ? py::object(py::float_(r.t_reached)) : py::object(py::none());
  d["reason"] = r.reason;
  d["signal"] = r.signal;
  py::list names, units, data;
  for (std::size_t c = 0; c < r.columns.size(); ++c) {
    names.append(r.columns[c].name);
    units.append(r.columns[c].unit);
    data.append(ToArray(std::move(outcome.columns[c])));
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
    e["name"] = outcome.event_names[i];
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
    batch_ = std::make_unique<run::Batch>(BatchModels(), 1);
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
    std::vector<run::BatchOutcome> outcomes = RunJobs({ToJob(kwargs)}, 1, handle_sigint);
    return ToPython(std::move(outcomes.front()));
  }

  // Results in input order; `threads` workers take the next run as they
  // finish one. Ctrl-C: the runs under way end at their last row, the others
  // are not run.
  py::list RunMany(const py::list& requests, int threads, bool handle_sigint) {
    std::vector<run::BatchJob> jobs;
    for (const py::handle& r : requests) {
      if (!py::isinstance<py::dict>(r)) throw py::type_error("run_many takes a list of dicts of run() keywords");
      jobs.push_back(ToJob(py::reinterpret_borrow<py::dict>(r)));
    }
    if (threads < 1) throw py::value_error("run_many: threads must be at least 1");
    std::vector<run::BatchOutcome> outcomes = RunJobs(std::move(jobs), threads, handle_sigint);
    py::list out;
    for (run::BatchOutcome& o : outcomes) out.append(ToPython(std::move(o)));
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
  // The jobs on the model's batch, without the GIL. Its workers keep their
  // built models from call to call (a run again on the same settings is not
  // rebuilt); a call from another Python thread while one is under way runs
  // on a batch of its own, built afresh.
  std::vector<run::BatchOutcome> RunJobs(std::vector<run::BatchJob> jobs, int threads, bool handle_sigint) {
    const py::gil_scoped_release unlocked;
    const SigintGuard guard(handle_sigint);
    for (run::BatchJob& job : jobs) job.options.interrupt = guard.flag();
    std::unique_lock<std::mutex> mine(batch_mutex_, std::try_to_lock);
    std::unique_ptr<run::Batch> spare;
    if (!mine.owns_lock()) spare = std::make_unique<run::Batch>(BatchModels(), threads);
    run::Batch& batch = mine.owns_lock() ? *batch_ : *spare;
    batch.SetThreads(threads);
    return batch.Run(jobs);
  }

  std::vector<run::BatchModel> BatchModels() const { return {{model_->description(), base_}}; }

  std::string path_;
  diagrams::LoadOptions base_;
  std::unique_ptr<run::Model> model_;
  std::unique_ptr<run::Batch> batch_;  // run()'s and run_many's, one Python thread at a time
  std::mutex batch_mutex_;
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
