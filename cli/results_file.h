#pragma once
// ResultsFile: the results CSV written as the run computes it.
//
// Rows are formatted as they come (blocks::RowSink) into a 64 KiB buffer
// that is written out whenever it fills, so memory stays bounded and a run
// that is interrupted, or fails, leaves every row it took on disk, each one
// complete (the buffer only ever holds whole rows). A write error is kept
// and reported by Close; the run itself goes on, and the file stays as far
// as it got, to be named as cut (its rows before the cut are still worth
// having).

#include <cstdint>
#include <string>
#include <vector>

#include "blocks/outputs/results.h"
#include "cli/output_folder.h"

namespace mechflow::cli {

class ResultsFile final : public blocks::RowSink {
 public:
  // Creates `name` in `folder` and writes the header. Throws WriteError.
  ResultsFile(const OutputFolder& folder, const std::string& name, const std::vector<std::string>& columns);
  ~ResultsFile() override;
  ResultsFile(const ResultsFile&) = delete;
  ResultsFile& operator=(const ResultsFile&) = delete;

  void WriteRow(const double* values, int count) override;
  // The file stops before the row that would take it past `bytes` (the
  // output budget: rows at events can outnumber the estimate); stopped()
  // then says so, and the run is to end.
  void SetByteLimit(std::uint64_t bytes) { limit_ = bytes; }
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
  std::string stopped_;
  long long rows_ = 0;
};

}  // namespace mechflow::cli
