#include "analysis/fit/residuals.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "blocks/outputs/csv.h"

namespace mechflow::analysis::fit {

double Evaluation::Cost() const {
  double sum = 0.0;
  for (const double r : residuals) sum += r * r;
  return sum;
}

std::vector<run::BatchModel> ExperimentModels(const Setup& setup) {
  std::vector<run::BatchModel> models;
  for (const Experiment& e : setup.experiments) {
    run::BatchModel m{setup.description, setup.common};
    m.options.variants.insert(m.options.variants.end(), e.variants.begin(), e.variants.end());
    m.options.overrides.insert(m.options.overrides.end(), e.overrides.begin(), e.overrides.end());
    models.push_back(std::move(m));
  }
  return models;
}

Residuals::Residuals(const Setup& setup) : setup_(setup), batch_(ExperimentModels(setup), setup.threads) {
  for (const Match& m : setup.matches) {
    if (!m.is_signal()) {
      column_.push_back(-1);
      continue;
    }
    auto it = std::find(signals_.begin(), signals_.end(), m.signal);
    if (it == signals_.end()) it = signals_.insert(signals_.end(), m.signal);
    column_.push_back(1 + static_cast<int>(it - signals_.begin()));
  }
  penalty_.assign(setup.matches.size(), 0.0);
  for (const Experiment& e : setup.experiments) {
    for (const Match& m : setup.matches) size_ += m.is_signal() ? static_cast<int>(e.times.size()) : 1;
    for (std::size_t k = 0; k < setup.matches.size(); ++k)
      for (const double v : e.measured[k]) penalty_[k] = std::max(penalty_[k], std::abs(v));
  }
  for (std::size_t k = 0; k < penalty_.size(); ++k)
    penalty_[k] = 10.0 * (penalty_[k] > 0 ? penalty_[k] : 1.0) * setup.matches[k].weight;
  for (const Match& m : setup.matches) figures_ = figures_ || !m.is_signal();
}

std::vector<Evaluation> Residuals::EvaluateUnit(const std::vector<std::vector<double>>& points) {
  std::vector<std::vector<double>> values;
  for (const auto& u : points) values.push_back(FromUnit(setup_.parameters, u));
  return Evaluate(values);
}

namespace {

// An evaluation as bytes for the other processes, and back: raw doubles (the
// same bits on every process of one machine type), strings with their lengths.
void Put(std::string* out, std::size_t n) { out->append(reinterpret_cast<const char*>(&n), sizeof n); }
void Put(std::string* out, const std::vector<double>& v) {
  Put(out, v.size());
  out->append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(double));
}

std::string Pack(const Evaluation& e) {
  std::string out;
  Put(&out, e.residuals);
  Put(&out, e.simulated.size());
  for (const auto& experiment : e.simulated) {
    Put(&out, experiment.size());
    for (const auto& match : experiment) Put(&out, match);
  }
  Put(&out, e.failures.size());
  for (const std::string& f : e.failures) {
    Put(&out, f.size());
    out += f;
  }
  return out;
}

class Reader {
 public:
  explicit Reader(const std::string& bytes) : bytes_(bytes) {}
  std::size_t Size() {
    std::size_t n = 0;
    std::memcpy(&n, bytes_.data() + at_, sizeof n);
    at_ += sizeof n;
    return n;
  }
  std::vector<double> Doubles() {
    std::vector<double> v(Size());
    std::memcpy(v.data(), bytes_.data() + at_, v.size() * sizeof(double));
    at_ += v.size() * sizeof(double);
    return v;
  }
  std::string Text() {
    const std::size_t n = Size();
    std::string s = bytes_.substr(at_, n);
    at_ += n;
    return s;
  }
  bool done() const { return at_ >= bytes_.size(); }

 private:
  const std::string& bytes_;
  std::size_t at_ = 0;
};

Evaluation Unpack(Reader* in) {
  Evaluation e;
  e.residuals = in->Doubles();
  e.simulated.resize(in->Size());
  for (auto& experiment : e.simulated) {
    experiment.resize(in->Size());
    for (auto& match : experiment) match = in->Doubles();
  }
  e.failures.resize(in->Size());
  for (std::string& f : e.failures) f = in->Text();
  return e;
}

}  // namespace

std::vector<Evaluation> Residuals::Evaluate(const std::vector<std::vector<double>>& points) {
  for (const std::vector<double>& values : points)
    if (Broken(setup_.constraints, setup_.parameters, values).empty())
      runs_ += static_cast<long long>(setup_.experiments.size());
  const Processes& processes = setup_.processes;
  if (processes.size <= 1) return EvaluateHere(points);
  // this process's share: points rank, rank + size, ...
  std::vector<std::vector<double>> mine;
  for (std::size_t p = processes.rank; p < points.size(); p += processes.size) mine.push_back(points[p]);
  std::string packed;
  for (const Evaluation& e : EvaluateHere(mine)) packed += Pack(e);
  const std::vector<std::string> parts = processes.all_gather(packed);
  std::vector<Evaluation> all(points.size());
  for (int r = 0; r < processes.size; ++r) {
    Reader in(parts.at(r));
    for (std::size_t p = r; p < points.size(); p += processes.size) all[p] = Unpack(&in);
  }
  return all;
}

std::vector<Evaluation> Residuals::EvaluateHere(const std::vector<std::vector<double>>& points) {
  std::vector<run::BatchJob> jobs;
  std::vector<std::string> broken;
  for (const std::vector<double>& values : points) {
    broken.push_back(Broken(setup_.constraints, setup_.parameters, values));
    if (!broken.back().empty()) continue;
    for (std::size_t e = 0; e < setup_.experiments.size(); ++e) {
      const Experiment& experiment = setup_.experiments[e];
      run::BatchJob job;
      job.model = static_cast<int>(e);
      for (std::size_t j = 0; j < values.size(); ++j) job.set.emplace_back(setup_.parameters[j].name, values[j]);
      job.options.log = signals_;
      job.options.times = experiment.times;
      if (!figures_)  // nothing after the last measurement is needed; a figure may come later
        job.options.t_end = experiment.times.back();
      job.options.interrupt = setup_.interrupt;
      jobs.push_back(std::move(job));
    }
  }
  const std::vector<run::BatchOutcome> outcomes = batch_.Run(jobs);
  std::vector<Evaluation> evaluations;
  std::size_t first = 0;
  for (std::size_t p = 0; p < points.size(); ++p) {
    if (broken[p].empty()) {
      evaluations.push_back(Collect(points[p], outcomes, first));
      first += setup_.experiments.size();
      continue;
    }
    Evaluation ev;  // not run: as a run that failed at once
    ev.failures.push_back(broken[p] + " (not run)");
    for (const Experiment& e : setup_.experiments) {
      ev.simulated.emplace_back();
      for (std::size_t k = 0; k < setup_.matches.size(); ++k) {
        const std::size_t n = setup_.matches[k].is_signal() ? e.times.size() : 1;
        ev.residuals.insert(ev.residuals.end(), n, penalty_[k]);
        ev.simulated.back().emplace_back(n, std::numeric_limits<double>::quiet_NaN());
      }
    }
    evaluations.push_back(std::move(ev));
  }
  return evaluations;
}

Evaluation Residuals::Collect(const std::vector<double>& values, const std::vector<run::BatchOutcome>& outcomes,
                              std::size_t first) const {
  Evaluation ev;
  ev.residuals.reserve(size_);
  for (std::size_t e = 0; e < setup_.experiments.size(); ++e) {
    const Experiment& experiment = setup_.experiments[e];
    const run::BatchOutcome& outcome = outcomes[first + e];
    const std::size_t n = experiment.times.size();
    // rows are at exactly the measured times, as many as the run reached
    const std::size_t reached = outcome.columns.empty() ? 0 : std::min(n, outcome.columns.front().size());
    if (reached < n) {
      std::string at;
      for (std::size_t j = 0; j < values.size(); ++j)
        at += (j ? ", " : "") + setup_.parameters[j].name + "=" + blocks::CsvNumber(values[j]);
      const std::string what = outcome.result.status == run::Status::kOk ? "ended" : "failed";
      ev.failures.push_back("the run for " + experiment.file + " at " + at + " " + what + " at t = " +
                            blocks::CsvNumber(outcome.result.t_reached) + " s" +
                            (outcome.result.reason.empty() ? "" : ": " + outcome.result.reason) + " (" +
                            std::to_string(n - reached) + " measured instants not reached)");
    }
    ev.simulated.emplace_back();
    for (std::size_t k = 0; k < setup_.matches.size(); ++k) {
      const Match& match = setup_.matches[k];
      if (!match.is_signal()) {
        double sim = std::numeric_limits<double>::quiet_NaN();
        for (const blocks::ReportFigure& f : outcome.result.figures)
          if (f.label == match.figure && f.found) sim = match.kind == Match::Kind::kFigureValue ? f.value : f.time;
        ev.residuals.push_back(std::isfinite(sim) ? match.weight * (sim - experiment.measured[k][0]) : penalty_[k]);
        ev.simulated.back().push_back({sim});
        continue;
      }
      std::vector<double> sim(n, std::numeric_limits<double>::quiet_NaN());
      for (std::size_t i = 0; i < reached; ++i) sim[i] = outcome.columns[column_[k]][i];
      const double w = setup_.matches[k].weight;
      for (std::size_t i = 0; i < n; ++i)
        ev.residuals.push_back(i < reached && std::isfinite(sim[i]) ? w * (sim[i] - experiment.measured[k][i])
                                                                    : penalty_[k]);
      ev.simulated.back().push_back(std::move(sim));
    }
  }
  return ev;
}

}  // namespace mechflow::analysis::fit
