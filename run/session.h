#pragma once
// run::Session: one run of a model taken in steps, its held inputs set
// between them (the co-simulation of fmi/ drives a diagram so).
//
//   run::Model model("oscillator.xml");
//   run::Session s(model);            // the model's current settings
//   s.SetInput(0, 2.0);               // a top-level <input>, in its unit
//   s.Start();
//   while (s.time() < 1.0) { s.AdvanceTo(s.time() + 0.01); s.Row(); }
//   s.Finish();
//
// Advancing to the output times of the diagram's grid gives the rows
// `mechflow run` writes (the simulator pauses inside a step and goes on
// from there; blocks/solver/simulator.h). An input set between two advances
// is held from the current time on: the integrator restarts there.
// No rows are kept; Row() is the logged columns now.

#include <memory>
#include <string>
#include <vector>

#include "run/model.h"

namespace mechflow::run {

class Session {
 public:
  // Builds the run from `model` as it stands (its Set values); the model
  // must outlive the session and not be changed while it lives.
  explicit Session(Model& model, const RunOptions& options = {});

  const std::vector<diagrams::DiagramInput>& inputs() const { return loaded_->inputs; }
  const std::vector<Column>& columns() const { return prepared_.columns(); }  // time first
  const blocks::SolverOptions& solver() const { return sim().options(); }

  // Input i's value in its unit, from now on (before Start: from t_start).
  void SetInput(int i, double value);
  double Input(int i) const { return inputs_[i] / loaded_->inputs[i].to_si; }

  // From t_start (once; a fresh Session runs it again).
  void Start();
  // Integrates to t (t_start <= t <= t_end); false when the run ended short
  // of it: failure() says why, time() where.
  bool AdvanceTo(double t);
  double time() const { return sim().time(); }
  bool ok() const { return sim().outcome().ok; }
  std::string failure() const;
  // The logged columns at time(), time first, in the columns' units (with
  // the inputs as set: an output fed through from one shows it at once).
  const std::vector<double>& Row();
  RunResult Finish();

 private:
  void Apply();  // the inputs into the run's held values
  void TakeInputs();  // inputs set since the last step: into the run, from now on
  blocks::Simulator& sim() const { return *sim_; }

  PreparedRun prepared_;
  const diagrams::LoadedDiagram* loaded_ = nullptr;
  blocks::Simulator* sim_ = nullptr;  // the prepared run's
  std::vector<double> inputs_;  // SI
  std::vector<int> input_offsets_;  // their discrete states in the run's context
  std::vector<int> row_signals_;
  std::vector<double> row_factors_, row_;
  bool started_ = false, finished_ = false, changed_ = false;
};

}  // namespace mechflow::run
