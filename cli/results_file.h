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
  // The same on `fd`, a descriptor of standard output (--results -), owned
  // from now on.
  ResultsFile(int fd, const std::vector<std::string>& columns);

  // The file stops before the row that would take it past `bytes` (the
  // output budget: rows at events can outnumber the estimate); stopped()
  // then says so, and the run is to end.
  void SetByteLimit(std::uint64_t bytes);
};

// While it lives, standard output carries the results CSV and nothing else
// (--results -): descriptor 1 points at standard error, so that whatever
// else would print there (a control script's print, a library) goes with
// the messages, and the results go to the original standard output through
// the descriptor TakeResultsDescriptor hands out. Restores descriptor 1 at
// the end.
class StandardOutputForResults {
 public:
  StandardOutputForResults();  // throws InputError when the descriptors cannot be copied
  ~StandardOutputForResults();
  StandardOutputForResults(const StandardOutputForResults&) = delete;
  StandardOutputForResults& operator=(const StandardOutputForResults&) = delete;

  // A new descriptor of the original standard output, for ResultsFile.
  int TakeResultsDescriptor() const;

 private:
  int saved_ = -1;
};

}  // namespace mechflow::cli
