#pragma once
// ResultsFile: the results CSV of `run` and `sweep`, streamed into the output
// folder as the run computes it (run::CsvFileSink: buffered, whole rows,
// kept as far as it got when a write fails), within the output budget.

#include <cstdint>
#include <string>
#include <vector>

#include "cli/output_folder.h"
#include "run/sinks.h"

namespace mechflow::cli {

class ResultsFile final : public run::CsvFileSink {
 public:
  // Creates `name` in `folder` and writes the header. Throws WriteError.
  ResultsFile(const OutputFolder& folder, const std::string& name, const std::vector<std::string>& columns);

  // The file stops before the row that would take it past `bytes` (the
  // output budget: rows at events can outnumber the estimate); stopped()
  // then says so, and the run is to end.
  void SetByteLimit(std::uint64_t bytes);
};

}  // namespace mechflow::cli
