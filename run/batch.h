#pragma once
// run::Batch: many runs of loaded diagrams, several at a time on threads.
//
//   run::Batch batch({{description, options}}, 2);   // models to run, threads
//   std::vector<run::BatchJob> jobs = ...;             // model, --set values, rows wanted
//   const std::vector<run::BatchOutcome> done = batch.Run(jobs);  // by index
//
// Each worker thread keeps its own run::Model of every model it has run,
// made from the description read once (never re-parsed). A job runs with
// its model's options and its own --set values over them, nothing of an
// earlier job's; the model is rebuilt only when those differ from what its
// last run was built with (run/model.h), so a run gives the same numbers on
// any thread, alone or in a batch, whichever jobs came before. Workers take
// the jobs in index order from a shared counter; outcomes are kept by index,
// so the order in which runs finish changes nothing. The workers' models last
// from one Run to the next (an optimiser's many rounds of runs).

#include <atomic>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "run/model.h"

namespace mechflow::run {

// A model a batch runs: the description and how it is loaded (variants, --set).
struct BatchModel {
  diagrams::DiagramDescription description;
  LoadOptions options;
};

struct BatchJob {
  int model = 0;                                                // index into the batch's models
  std::vector<std::pair<std::string, double>> set;              // Model::Set, in order, after the model's options
  std::vector<std::pair<std::string, std::string>> set_expressions;  // Model::SetExpression, after `set`
  RunOptions options;  // an interrupt flag set before the job starts: not run (kInterrupted)
};

// Why a job has no run: it did run (kNone), or what stopped it first.
enum class Refusal {
  kNone,
  kInput,        // InputError: a --set name or value its model refuses, a bad log name
  kSimulation,   // SimulationError thrown by the run (a script error, a start that fails)
  kInterrupted,  // the interrupt flag was set before it started
  kOther,        // any other exception
};

struct BatchOutcome {
  RunResult result;  // a job with no run: status kFailed (kInterrupted) and the reason
  Refusal refused = Refusal::kNone;
  std::vector<std::vector<double>> columns;  // the rows (MemorySink), time first
  std::vector<std::string> event_names;      // result.events named as the event log names them
};

class Batch {
 public:
  // `threads` >= 1: runs at a time.
  Batch(std::vector<BatchModel> models, int threads);
  ~Batch();
  Batch(const Batch&) = delete;
  Batch& operator=(const Batch&) = delete;

  // Every job, `threads` at a time (fewer when fewer jobs); outcomes by index.
  // A run that throws (a value its model refuses, a script error) is an
  // outcome with status kFailed and the message, not an exception.
  std::vector<BatchOutcome> Run(const std::vector<BatchJob>& jobs);

  // Runs at a time from the next Run on (>= 1); the workers' models stay.
  void SetThreads(int threads);
  int threads() const { return threads_; }
  long long runs() const { return runs_; }  // runs made so far

 private:
  // A worker's models, one per BatchModel, made at their first run.
  using WorkerModels = std::vector<std::unique_ptr<Model>>;
  BatchOutcome RunOne(const BatchJob& job, WorkerModels* models) const;

  std::vector<BatchModel> models_;
  int threads_;
  std::vector<WorkerModels> workers_;  // one per thread, kept between Runs
  std::atomic<long long> runs_{0};
};

}  // namespace mechflow::run
