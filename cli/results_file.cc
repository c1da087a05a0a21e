#include "cli/results_file.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "cli/output_budget.h"

namespace mechflow::cli {
namespace {

constexpr std::size_t kBufferBytes = 64 * 1024;

}  // namespace

ResultsFile::ResultsFile(const OutputFolder& folder, const std::string& name, const std::vector<std::string>& columns)
    : path_(folder.PathOf(name)), fd_(folder.Create(name)) {
  buffer_.reserve(kBufferBytes + 4096);
  buffer_ = blocks::CsvHeader(columns);
}

ResultsFile::~ResultsFile() { Close(); }

void ResultsFile::WriteRow(const double* values, int count) {
  if (!stopped_.empty()) return;
  const std::size_t before = buffer_.size();
  blocks::AppendCsvRow(values, count, &buffer_);
  if (static_cast<std::uint64_t>(bytes_) + buffer_.size() > limit_) {
    buffer_.resize(before);
    stopped_ = "'" + path_ + "' reached the output budget of " + ByteSizeText(static_cast<double>(limit_)) +
               " after " + std::to_string(rows_) + " rows (more than estimated before the run: rows at events); the rows up to " +
               "there are written; raise the output interval, shorten t_end, log fewer signals, or raise the budget " +
               "with --max-output 8G";
    return;
  }
  ++rows_;
  if (buffer_.size() >= kBufferBytes) Flush();
}

void ResultsFile::Fail(const std::string& why, const std::string& where) {
  why_ = why;
  error_ = "error writing '" + path_ + "' " + where + ": " + why + "; the file is cut there, its rows before are kept";
}

void ResultsFile::Flush() {
  std::size_t done = 0;
  while (error_.empty() && done < buffer_.size()) {
    const ssize_t n = ::write(fd_, buffer_.data() + done, buffer_.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0)
      Fail(n < 0 ? std::strerror(errno) : "nothing more could be written",
           "after " + std::to_string(bytes_ + done) + " bytes");
    else
      done += static_cast<std::size_t>(n);
  }
  bytes_ += static_cast<long long>(done);
  buffer_.clear();
}

std::string ResultsFile::Close() {
  if (fd_ < 0) return error_;
  Flush();
  if (::close(fd_) != 0 && error_.empty()) Fail(std::strerror(errno), "at close");
  fd_ = -1;
  return error_;
}

}  // namespace mechflow::cli
