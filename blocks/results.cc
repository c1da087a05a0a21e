#include "blocks/results.h"

#include <stdexcept>

#include "blocks/csv.h"

namespace mechflow::blocks {

Results::Results(std::vector<std::string> signal_columns) {
  columns_.push_back("time");
  columns_.insert(columns_.end(), signal_columns.begin(), signal_columns.end());
}

int Results::FindColumn(const std::string& name) const {
  for (int i = 0; i < num_columns(); ++i)
    if (columns_[i] == name) return i;
  return -1;
}

std::vector<double> Results::Column(int column) const {
  std::vector<double> out(num_rows());
  for (int r = 0; r < num_rows(); ++r) out[r] = at(r, column);
  return out;
}

void Results::AddRow(const double* values) { values_.insert(values_.end(), values, values + columns_.size()); }

void Results::WriteCsv(std::ostream& out) const {
  for (int c = 0; c < num_columns(); ++c) out << (c ? "," : "") << CsvField(columns_[c]);
  out << '\n';
  for (int r = 0; r < num_rows(); ++r) {
    for (int c = 0; c < num_columns(); ++c) out << (c ? "," : "") << CsvNumber(at(r, c));
    out << '\n';
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
