#include "blocks/outputs/results.h"

#include <algorithm>
#include <stdexcept>

#include "blocks/outputs/csv.h"

namespace mechflow::blocks {

Results::Results(std::vector<std::string> signal_columns) {
  columns_.push_back("time");
  columns_.insert(columns_.end(), signal_columns.begin(), signal_columns.end());
  ranges_.resize(columns_.size());
}

int Results::FindColumn(const std::string& name) const {
  for (int i = 0; i < num_columns(); ++i)
    if (columns_[i] == name) return i;
  return -1;
}

double Results::at(int row, int column) const {
  if (!keep_all_) throw std::logic_error("Results::at: the rows were streamed, not kept");
  return values_[row * columns_.size() + column];
}

std::vector<double> Results::Column(int column) const {
  if (!keep_all_) {
    const auto it = std::find(kept_.begin(), kept_.end(), column);
    if (it == kept_.end()) throw std::logic_error("Results::Column: column '" + columns_.at(column) + "' was not kept");
    return kept_values_[it - kept_.begin()];
  }
  std::vector<double> out(num_rows());
  for (int r = 0; r < num_rows(); ++r) out[r] = at(r, column);
  return out;
}

void Results::Stream(RowSink* sink, std::vector<int> keep) {
  sink_ = sink;
  keep_all_ = false;
  values_.clear();
  values_.shrink_to_fit();
  if (!keep.empty()) keep.insert(keep.begin(), 0);  // time with the kept columns
  std::sort(keep.begin(), keep.end());
  keep.erase(std::unique(keep.begin(), keep.end()), keep.end());
  kept_ = std::move(keep);
  kept_values_.assign(kept_.size(), {});
}

void Results::Clear() {
  rows_ = 0;
  last_time_ = 0.0;
  ranges_.assign(columns_.size(), {});
  values_.clear();
  for (std::vector<double>& column : kept_values_) column.clear();
  figures_.clear();
}

void Results::Reserve(int rows) {
  if (keep_all_) values_.reserve(static_cast<std::size_t>(rows) * columns_.size());
  for (std::vector<double>& column : kept_values_) column.reserve(static_cast<std::size_t>(rows));
  if (sink_) sink_->ExpectRows(rows);
}

void Results::AddRow(const double* values) {
  const double t = values[0];
  for (std::size_t c = 0; c < columns_.size(); ++c) {
    ColumnRange& r = ranges_[c];
    if (values[c] < r.min) r = {values[c], t, r.max, r.max_time};
    if (values[c] > r.max) r = {r.min, r.min_time, values[c], t};
  }
  ++rows_;
  last_time_ = t;
  if (sink_) sink_->WriteRow(values, num_columns());
  if (keep_all_) {
    values_.insert(values_.end(), values, values + columns_.size());
    return;
  }
  for (std::size_t k = 0; k < kept_.size(); ++k) kept_values_[k].push_back(values[kept_[k]]);
}

std::string CsvHeader(const std::vector<std::string>& columns) {
  std::string out;
  for (std::size_t c = 0; c < columns.size(); ++c) out += (c ? "," : "") + CsvField(columns[c]);
  return out + '\n';
}

void AppendCsvRow(const double* values, int count, std::string* out) {
  for (int c = 0; c < count; ++c) {
    if (c) *out += ',';
    *out += CsvNumber(values[c]);
  }
  *out += '\n';
}

void Results::WriteCsv(std::ostream& out) const {
  if (!keep_all_) throw std::logic_error("Results::WriteCsv: the rows were streamed, not kept");
  out << CsvHeader(columns_);
  std::string row;
  for (int r = 0; r < num_rows(); ++r) {
    row.clear();
    AppendCsvRow(&values_[r * columns_.size()], num_columns(), &row);
    out << row;
  }
}

void Results::WriteFiguresCsv(std::ostream& file) const {
  file << "label,kind,signal,value,unit,time\n";
  for (const ReportFigure& f : figures_) {
    const std::string value = f.found ? CsvNumber(f.value) : "", time = f.found ? CsvNumber(f.time) : "";
    file << CsvField(f.label) << ',' << ReportKindName(f.kind) << ',' << CsvField(f.signal) << ',' << value << ','
         << CsvField(f.unit) << ',' << time << '\n';
  }
}

}  // namespace mechflow::blocks
