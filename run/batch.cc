#include "run/batch.h"

#include <algorithm>
#include <cstring>
#include <exception>
#include <thread>

#include "blocks/solver/crossing_events.h"
#include "mech/errors.h"
#include "run/sinks.h"

namespace mechflow::run {

Batch::Batch(std::vector<BatchModel> models, int threads)
    : models_(std::move(models)), threads_(std::max(1, threads)), workers_(threads_) {}

Batch::~Batch() = default;

void Batch::SetThreads(int threads) {
  threads_ = std::max(1, threads);
  if (workers_.size() < static_cast<std::size_t>(threads_)) workers_.resize(threads_);
}

BatchOutcome Batch::RunOne(const BatchJob& job, WorkerModels* models) const {
  BatchOutcome outcome;
  const auto refuse = [&](Refusal why, Status status, const std::string& reason) {
    outcome.refused = why;
    outcome.result.status = status;
    outcome.result.reason = reason;
  };
  std::unique_ptr<Model>* model = nullptr;
  try {
    if (job.options.interrupt && *job.options.interrupt) {
      refuse(Refusal::kInterrupted, Status::kInterrupted,
             std::string("not run: interrupted by SIG") + sigabbrev_np(*job.options.interrupt));
      outcome.result.signal = *job.options.interrupt;
      return outcome;
    }
    if (models->empty()) models->resize(models_.size());
    model = &models->at(job.model);
    const BatchModel& base = models_[job.model];
    if (!*model) *model = std::make_unique<Model>(base.description, base.options);
    (*model)->SetOptions(base.options);
    for (const auto& [name, value] : job.set) (*model)->Set(name, value);
    for (const auto& [name, expression] : job.set_expressions) (*model)->SetExpression(name, expression);
    MemorySink sink;
    PreparedRun prepared = (*model)->Prepare(job.options);
    outcome.result = prepared.Run(&sink);
    outcome.columns = sink.TakeColumns();
    outcome.columns.resize(outcome.result.columns.size());  // no rows: empty columns
    for (const blocks::EventRecord& e : outcome.result.events)
      outcome.event_names.push_back(blocks::EventName(*prepared.loaded().diagram, e));
    return outcome;
  } catch (const InputError& e) {
    refuse(Refusal::kInput, Status::kFailed, e.what());
  } catch (const SimulationError& e) {
    refuse(Refusal::kSimulation, Status::kFailed, e.what());
  } catch (const std::exception& e) {
    refuse(Refusal::kOther, Status::kFailed, e.what());
  }
  if (model) model->reset();  // the next run of this worker starts from a model made afresh
  return outcome;
}

std::vector<BatchOutcome> Batch::Run(const std::vector<BatchJob>& jobs) {
  std::vector<BatchOutcome> outcomes(jobs.size());
  std::atomic<std::size_t> next{0};
  const auto work = [&](WorkerModels* models) {
    for (std::size_t k = next++; k < jobs.size(); k = next++) outcomes[k] = RunOne(jobs[k], models);
  };
  const int n = static_cast<int>(std::min<std::size_t>(threads_, jobs.size()));
  std::vector<std::thread> threads;
  for (int j = 1; j < n; ++j) {
    try {
      threads.emplace_back(work, &workers_[j]);
    } catch (const std::exception&) {  // no thread to be had (a process limit): the others do its share
      break;
    }
  }
  work(&workers_[0]);
  for (std::thread& t : threads) t.join();
  runs_ += static_cast<long long>(jobs.size());
  return outcomes;
}

}  // namespace mechflow::run
