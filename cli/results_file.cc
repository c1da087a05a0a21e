#include "cli/results_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>

#include "cli/output_budget.h"

namespace mechflow::cli {

ResultsFile::ResultsFile(const OutputFolder& folder, const std::string& name, const std::vector<std::string>& columns)
    : run::CsvFileSink(folder.Create(name), folder.PathOf(name), columns) {}

ResultsFile::ResultsFile(int fd, const std::vector<std::string>& columns)
    : run::CsvFileSink(fd, "standard output", columns) {}

void ResultsFile::SetByteLimit(std::uint64_t bytes) {
  run::CsvFileSink::SetByteLimit(bytes, [this, bytes](long long rows) {
    return "'" + path() + "' reached the output budget of " + ByteSizeText(static_cast<double>(bytes)) + " after " +
           std::to_string(rows) + " rows (more than estimated before the run: rows at events); the rows up to " +
           "there are written; raise the output interval, shorten t_end, log fewer signals, or raise the budget " +
           "with --max-output 8G";
  });
}

StandardOutputForResults::StandardOutputForResults() {
  // what is buffered for standard output goes there before it changes
  std::cout.flush();
  std::fflush(stdout);
  saved_ = ::fcntl(STDOUT_FILENO, F_DUPFD_CLOEXEC, 3);
  if (saved_ < 0) throw InputError(std::string("--results -: cannot use standard output: ") + std::strerror(errno));
  if (::dup2(STDERR_FILENO, STDOUT_FILENO) < 0) {
    const std::string why = std::strerror(errno);
    ::close(saved_);
    throw InputError("--results -: cannot use standard output: " + why);
  }
}

StandardOutputForResults::~StandardOutputForResults() {
  std::cout.flush();
  std::fflush(stdout);
  ::dup2(saved_, STDOUT_FILENO);
  ::close(saved_);
}

int StandardOutputForResults::TakeResultsDescriptor() const {
  const int fd = ::fcntl(saved_, F_DUPFD_CLOEXEC, 3);
  if (fd < 0) throw InputError(std::string("--results -: cannot use standard output: ") + std::strerror(errno));
  return fd;
}

}  // namespace mechflow::cli
