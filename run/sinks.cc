#include "run/sinks.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "mech/errors.h"

namespace mechflow::run {
namespace {

constexpr std::size_t kBufferBytes = 64 * 1024;

int CreateFile(const std::string& path) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw InputError("cannot create '" + path + "': " + std::strerror(errno));
  return fd;
}

}  // namespace

CsvFileSink::CsvFileSink(const std::string& path, const std::vector<std::string>& columns)
    : CsvFileSink(CreateFile(path), path, columns) {}

CsvFileSink::CsvFileSink(int fd, const std::string& path, const std::vector<std::string>& columns)
    : path_(path), fd_(fd) {
  buffer_.reserve(kBufferBytes + 4096);
  buffer_ = blocks::CsvHeader(columns);
}

CsvFileSink::~CsvFileSink() { Close(); }

void CsvFileSink::SetByteLimit(std::uint64_t bytes, std::function<std::string(long long rows)> why) {
  limit_ = bytes;
  limit_message_ = std::move(why);
}

void CsvFileSink::WriteRow(const double* values, int count) {
  if (!stopped_.empty()) return;
  const std::size_t before = buffer_.size();
  blocks::AppendCsvRow(values, count, &buffer_);
  if (static_cast<std::uint64_t>(bytes_) + buffer_.size() > limit_) {
    buffer_.resize(before);
    stopped_ = limit_message_ ? limit_message_(rows_) : "'" + path_ + "' reached its byte limit";
    return;
  }
  ++rows_;
  if (buffer_.size() >= kBufferBytes) Flush();
}

void CsvFileSink::Fail(const std::string& why, const std::string& where) {
  why_ = why;
  error_ = "error writing '" + path_ + "' " + where + ": " + why + "; the file is cut there, its rows before are kept";
}

void CsvFileSink::Flush() {
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

std::string CsvFileSink::Close() {
  if (fd_ < 0) return error_;
  Flush();
  if (::close(fd_) != 0 && error_.empty()) Fail(std::strerror(errno), "at close");
  fd_ = -1;
  return error_;
}

void MemorySink::WriteRow(const double* values, int count) {
  if (columns_.empty()) {
    columns_.resize(static_cast<std::size_t>(count));
    for (std::vector<double>& column : columns_) column.reserve(static_cast<std::size_t>(expected_rows_));
  }
  for (int c = 0; c < count; ++c) columns_[c].push_back(values[c]);
}

}  // namespace mechflow::run
