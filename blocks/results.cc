#include "blocks/results.h"

#include <cstdio>
#include <stdexcept>

namespace mechflow::blocks {

namespace {

// A CSV field: quoted when it holds a separator, a quote or a line break.
std::string CsvField(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string out = "\"";
  for (const char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

}  // namespace


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
  char buffer[32];
  for (int r = 0; r < num_rows(); ++r) {
    for (int c = 0; c < num_columns(); ++c) {
      std::snprintf(buffer, sizeof buffer, "%.17g", at(r, c));
      out << (c ? "," : "") << buffer;
    }
    out << '\n';
  }
}

void Results::WriteFiguresCsv(std::ostream& file) const {
  file << "label,kind,signal,value,unit,time\n";
  char value[32] = "", time[32] = "";
  for (const ReportFigure& f : figures_) {
    value[0] = time[0] = '\0';
    if (f.found) {
      std::snprintf(value, sizeof value, "%.17g", f.value);
      std::snprintf(time, sizeof time, "%.17g", f.time);
    }
    file << CsvField(f.label) << ',' << ReportKindName(f.kind) << ',' << CsvField(f.signal) << ',' << value << ','
         << CsvField(f.unit) << ',' << time << '\n';
  }
}

}  // namespace mechflow::blocks
