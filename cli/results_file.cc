#include "cli/results_file.h"

#include "cli/output_budget.h"

namespace mechflow::cli {

ResultsFile::ResultsFile(const OutputFolder& folder, const std::string& name, const std::vector<std::string>& columns)
    : run::CsvFileSink(folder.Create(name), folder.PathOf(name), columns) {}

void ResultsFile::SetByteLimit(std::uint64_t bytes) {
  run::CsvFileSink::SetByteLimit(bytes, [this, bytes](long long rows) {
    return "'" + path() + "' reached the output budget of " + ByteSizeText(static_cast<double>(bytes)) + " after " +
           std::to_string(rows) + " rows (more than estimated before the run: rows at events); the rows up to " +
           "there are written; raise the output interval, shorten t_end, log fewer signals, or raise the budget " +
           "with --max-output 8G";
  });
}

}  // namespace mechflow::cli
