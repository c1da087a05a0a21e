#include "blocks/results.h"

#include <cstdio>
#include <fstream>
#include <stdexcept>

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
  for (int c = 0; c < num_columns(); ++c) out << (c ? "," : "") << columns_[c];
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

void Results::WriteCsv(const std::string& path) const {
  std::ofstream file(path);
  if (!file) throw std::runtime_error("cannot write '" + path + "'");
  WriteCsv(file);
  if (!file) throw std::runtime_error("error while writing '" + path + "'");
}

}  // namespace mechflow::blocks
