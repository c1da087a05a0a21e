#include "run/session.h"

#include <stdexcept>

namespace mechflow::run {

Session::Session(Model& model, const RunOptions& options)
    : prepared_(model.Prepare(options)) {
  loaded_ = &prepared_.loaded();
  sim_ = &prepared_.simulator();
  const blocks::Diagram& diagram = *loaded_->diagram;
  for (const diagrams::DiagramInput& in : loaded_->inputs) {
    inputs_.push_back(in.start);
    input_offsets_.push_back(diagram.layout(in.block).first_discrete);
  }
  const std::vector<blocks::SignalRef>& logged = loaded_->logged;
  for (const blocks::SignalRef& s : logged)
    for (int i = 0; i < s.width; ++i) {
      row_signals_.push_back(s.offset + i);
      row_factors_.push_back(s.column_factor);
    }
  if (options.log) throw std::logic_error("run::Session logs the diagram's <log>s");
  row_.assign(row_signals_.size() + 1, 0.0);
  sim().StreamRows(nullptr, {});
}

void Session::SetInput(int i, double value) {
  const double si = value * loaded_->inputs.at(i).to_si;
  if (si == inputs_[i]) return;
  inputs_[i] = si;
  changed_ = true;
}

void Session::Apply() {
  std::vector<double>& discrete = sim().mutable_context().discrete;
  for (std::size_t i = 0; i < inputs_.size(); ++i) discrete[input_offsets_[i]] = inputs_[i];
}

void Session::TakeInputs() {
  if (!changed_ || !started_ || finished_) return;
  Apply();
  sim().RestartHere();  // the outputs evaluated with them, the integrator restarted
  changed_ = false;
}

void Session::Start() {
  if (started_) throw std::logic_error("run::Session::Start: a session runs once");
  blocks::Simulator& sim = *sim_;
  sim.Start();
  started_ = true;
  // inputs set before the start hold from it
  bool differ = false;
  for (std::size_t i = 0; i < inputs_.size(); ++i) differ |= inputs_[i] != loaded_->inputs[i].start;
  if (differ) {
    Apply();
    sim.RestartHere();
  }
  changed_ = false;
  sim.EvaluateHere();
}

bool Session::AdvanceTo(double t) {
  if (!started_) throw std::logic_error("run::Session::AdvanceTo before Start");
  if (finished_) throw std::logic_error("run::Session::AdvanceTo after Finish");
  blocks::Simulator& sim = *sim_;
  TakeInputs();
  const bool reached = sim.AdvanceTo(t);
  if (reached) sim.EvaluateHere();
  return reached && sim.outcome().ok;
}

std::string Session::failure() const {
  const blocks::RunOutcome& o = sim().outcome();
  if (!o.ok) return o.failure;
  if (o.stopped) return o.stop_reason;
  return "the diagram's control script stopped the run";
}

const std::vector<double>& Session::Row() {
  TakeInputs();  // an output fed through from an input shows its new value at once
  const blocks::Simulator& sim = *sim_;
  const std::vector<double>& signals = sim.context().signals;
  row_[0] = sim.time();
  for (std::size_t c = 0; c < row_signals_.size(); ++c) row_[c + 1] = signals[row_signals_[c]] * row_factors_[c];
  return row_;
}

RunResult Session::Finish() {
  finished_ = true;
  RunResult r;
  r.outcome = sim().Finish();
  r.t_reached = r.outcome.t_reached;
  if (r.outcome.stopped) {
    r.status = Status::kStopped;
    r.reason = r.outcome.stop_reason;
  } else if (!r.outcome.ok) {
    r.status = Status::kFailed;
    r.reason = r.outcome.failure;
  }
  r.stats = sim().stats();
  r.events = sim().events();
  r.columns = columns();
  return r;
}

}  // namespace mechflow::run
