#include "run/results_table.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <optional>
#include <sstream>

#include "blocks/outputs/csv.h"
#include "blocks/support/excerpt.h"
#include "blocks/support/suggest.h"
#include "mech/errors.h"

namespace mechflow::run {
namespace {

// The fields of one CSV line (RFC 4180: "..." may hold commas, "" a quote).
std::vector<std::string> Fields(const std::string& line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') out.back() += '"', ++i;
      else if (c == '"') quoted = false;
      else out.back() += c;
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      out.emplace_back();
    } else if (c != '\r') {
      out.back() += c;
    }
  }
  return out;
}

// A field as the number it holds, the whole field (spaces around it
// aside): "1abc" and "0x10" are not numbers, nor are inf and nan here.
std::optional<double> FieldNumber(const std::string& field) {
  const auto first = field.find_first_not_of(" \t"), last = field.find_last_not_of(" \t");
  if (first == std::string::npos) return std::nullopt;
  const char* begin = field.data() + first;
  const char* end = field.data() + last + 1;
  if (*begin == '+') ++begin;  // from_chars takes no leading plus
  double value = 0.0;
  const auto [stop, error] = std::from_chars(begin, end, value);
  if (error != std::errc() || stop != end || !std::isfinite(value)) return std::nullopt;
  return value;
}

}  // namespace

ResultsColumns ReadResultsColumns(const std::string& file_text, const std::string& path,
                                  const std::vector<std::string>& wanted) {
  std::istringstream text{std::string(blocks::WithoutByteOrderMark(file_text))};
  std::string line;
  if (!std::getline(text, line)) throw InputError(path + ": empty, no header");
  const std::vector<std::string> header = Fields(line);
  std::vector<int> columns;
  for (const std::string& name : wanted) {
    const auto it = std::find(header.begin(), header.end(), name);
    if (it == header.end() || it == header.begin())
      throw InputError(path + ": no signal '" + blocks::Excerpt(name) + "'" + blocks::DidYouMean(name, header) +
                       "; columns: " +
                       blocks::Excerpt(blocks::JoinNames(std::vector<std::string>(header.begin() + 1, header.end())),
                                       200));
    columns.push_back(static_cast<int>(it - header.begin()));
  }
  ResultsColumns table;
  table.values.resize(wanted.size());
  for (int row = 2; std::getline(text, line); ++row) {
    if (line.empty()) continue;
    const std::vector<std::string> f = Fields(line);
    const std::string where = path + ":" + std::to_string(row);
    const auto number = [&](int c) {
      if (c >= static_cast<int>(f.size())) throw InputError(where + ": fewer fields than the header");
      const std::optional<double> v = FieldNumber(f[c]);
      if (!v) throw InputError(where + ": '" + blocks::Excerpt(f[c]) + "' is not a finite number");
      return *v;
    };
    const double t = number(0);
    // the resampling onto an even grid needs rising times; rows out of order
    // (two files joined, a sort gone wrong) would be averaged into nonsense
    if (!table.time.empty() && !(t > table.time.back()))
      throw InputError(where + ": time " + blocks::Excerpt(f[0]) + " is not after the row before (" +
                       blocks::CsvNumber(table.time.back()) + "); the rows must be in rising time order, each time "
                       "once (sort the file, or drop the repeated rows)");
    table.time.push_back(t);
    table.lines.push_back(row);
    for (std::size_t i = 0; i < columns.size(); ++i) table.values[i].push_back(number(columns[i]));
  }
  return table;
}

}  // namespace mechflow::run
