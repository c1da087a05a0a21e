#include "run/batch.h"

#include <algorithm>
#include <exception>
#include <thread>

#include "run/sinks.h"

namespace mechflow::run {

Batch::Batch(std::vector<BatchModel> models, int threads)
    : models_(std::move(models)), threads_(std::max(1, threads)), workers_(threads_) {}

Batch::~Batch() = default;

BatchOutcome Batch::RunOne(const BatchJob& job, WorkerModels* models) const {
  BatchOutcome outcome;
  try {
    if (models->empty()) models->resize(models_.size());
    std::unique_ptr<Model>& model = models->at(job.model);
    if (!model) model = std::make_unique<Model>(models_[job.model].description, models_[job.model].options);
    for (const auto& [name, value] : job.set) model->Set(name, value);
    MemorySink sink;
    outcome.result = model->Run(job.options, &sink);
    outcome.columns = sink.columns();
  } catch (const std::exception& e) {
    // the next run of this worker starts from a model made afresh
    if (!models->empty()) models->at(job.model).reset();
    outcome.result.status = Status::kFailed;
    outcome.result.reason = e.what();
  }
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
