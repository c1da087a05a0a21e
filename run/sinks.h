#pragma once
// Where a run's rows go (blocks::RowSink): a CSV file written as the run
// computes it, or the columns in memory. A run without a sink keeps no rows.

#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "blocks/outputs/results.h"

namespace mechflow::run {

// The results CSV, streamed. Rows are formatted as they come into a 64 KiB
// buffer that is written out whenever it fills, so memory stays bounded and
// a run that is interrupted, or fails, leaves every row it took on disk, each
// one complete (the buffer only ever holds whole rows). A write error is kept
// and reported by Close; the run itself goes on, and the file stays as far as
// it got, to be named as cut (its rows before the cut are still worth having).
class CsvFileSink : public blocks::RowSink {
 public:
  // Creates (or truncates) `path` and writes the header. Throws InputError.
  CsvFileSink(const std::string& path, const std::vector<std::string>& columns);
  // The same on a descriptor already open for writing (owned from now on),
  // `path` naming it in messages.
  CsvFileSink(int fd, const std::string& path, const std::vector<std::string>& columns);
  ~CsvFileSink() override;
  CsvFileSink(const CsvFileSink&) = delete;
  CsvFileSink& operator=(const CsvFileSink&) = delete;

  void WriteRow(const double* values, int count) override;
  // The file stops before the row that would take it past `bytes`; stopped()
  // then holds `why(rows written)`, and the run is to end.
  void SetByteLimit(std::uint64_t bytes, std::function<std::string(long long rows)> why);
  const std::string& stopped() const { return stopped_; }
  long long rows() const { return rows_; }  // rows in the file
  // Writes what is buffered and closes; "" or what went wrong.
  std::string Close();
  const std::string& path() const { return path_; }
  // Why the file is cut ("No space left on device"); "" while it is whole.
  const std::string& cut_reason() const { return why_; }

 private:
  void Flush();
  void Fail(const std::string& why, const std::string& where);

  std::string path_;
  int fd_ = -1;
  std::string buffer_;
  std::string error_, why_;
  long long bytes_ = 0;
  std::uint64_t limit_ = UINT64_MAX;
  std::function<std::string(long long)> limit_message_;
  std::string stopped_;
  long long rows_ = 0;
};

// Every row in memory, a vector per column (time first).
class MemorySink final : public blocks::RowSink {
 public:
  void WriteRow(const double* values, int count) override;
  // Each column is allocated once at the first row, this long (more rows
  // still fit: the columns then grow as vectors do).
  void ExpectRows(long rows) override { expected_rows_ = rows; }
  const std::vector<std::vector<double>>& columns() const { return columns_; }
  // The columns, moved out (the sink is empty after): a long run's rows are not copied.
  std::vector<std::vector<double>> TakeColumns() { return std::move(columns_); }
  long long rows() const { return columns_.empty() ? 0 : static_cast<long long>(columns_.front().size()); }

 private:
  std::vector<std::vector<double>> columns_;
  long expected_rows_ = 0;
};

}  // namespace mechflow::run
