#include "blocks/library/table.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>

#include "blocks/outputs/csv.h"
#include "blocks/support/excerpt.h"
#include "mech/errors.h"

namespace mechflow::blocks {
namespace {

// Checks one point against the points before it; `where` starts the message
// and `previous` names the row before ("row 2", "line 7").
void CheckPoint(double t, double y, const std::vector<double>& times, const std::string& where,
                const std::string& previous, const std::string& x) {
  if (!std::isfinite(t) || !std::isfinite(y))
    throw InputError(where + ": point (" + CsvNumber(t) + ", " + CsvNumber(y) + ") is not finite");
  if (!times.empty() && !(t > times.back()))
    throw InputError(where + ": " + (x == "t" ? "times" : "breakpoints") + " must increase strictly, but " + x +
                     " = " + CsvNumber(t) + " follows " + x + " = " + CsvNumber(times.back()) + " (" + previous + ")");
}

void CheckCount(const std::vector<double>& times, const std::string& source) {
  if (times.size() < 2)
    throw InputError(source + ": a table needs at least two points, got " + std::to_string(times.size()));
}

}  // namespace

TableBlock::TableBlock(const std::string& name, std::vector<double> times, std::vector<double> values)
    : Block("table", name), times_(std::move(times)), values_(std::move(values)) {
  DeclareOutputPort("y");
}

void TableBlock::DoCalcOutput(int, const BlockContext& ctx) const {
  const double t = ctx.time();
  double& y = ctx.output(0)[0];
  if (t <= times_.front()) {
    y = values_.front();
  } else if (t >= times_.back()) {
    y = values_.back();
  } else {
    // times_[i-1] <= t < times_[i]
    const size_t i = std::upper_bound(times_.begin(), times_.end(), t) - times_.begin();
    const double s = (t - times_[i - 1]) / (times_[i] - times_[i - 1]);
    y = values_[i - 1] + s * (values_[i] - values_[i - 1]);
  }
}

void TablePointsFromRows(const std::vector<std::vector<double>>& rows, std::vector<double>* times,
                         std::vector<double>* values, const std::string& x) {
  for (size_t i = 0; i < rows.size(); ++i) {
    const std::string where = "points row " + std::to_string(i + 1);
    if (rows[i].size() != 2)
      throw InputError(where + " has " + std::to_string(rows[i].size()) + " numbers; expected two (" + x + " y)");
    CheckPoint(rows[i][0], rows[i][1], *times, where, "row " + std::to_string(i), x);
    times->push_back(rows[i][0]);
    values->push_back(rows[i][1]);
  }
  CheckCount(*times, "points");
}

std::vector<NumberRow> ReadNumberRows(const std::string& file_text, const std::string& path,
                                      const std::string& expected) {
  std::istringstream in{std::string(WithoutByteOrderMark(file_text))};
  std::vector<NumberRow> rows;
  std::string line;
  int line_number = 0;
  bool header_allowed = true;
  while (std::getline(in, line)) {
    ++line_number;
    // '#' starts a comment; commas, semicolons and tabs separate like spaces
    const std::string text = line.substr(0, line.find('#'));
    std::string fields = text;
    for (char& c : fields)
      if (c == ',' || c == ';' || c == '\t' || c == '\r') c = ' ';
    NumberRow row{line_number, {}, false};
    int text_fields = 0;
    size_t pos = 0;
    while ((pos = fields.find_first_not_of(' ', pos)) != std::string::npos) {
      const size_t end = std::min(fields.find(' ', pos), fields.size());
      double v = 0;
      const auto [ptr, error] = std::from_chars(fields.data() + pos, fields.data() + end, v);
      if (error != std::errc() || ptr != fields.data() + end) {
        v = std::nan("");
        ++text_fields;
      }
      row.values.push_back(v);
      pos = end;
    }
    if (row.values.empty()) continue;
    const bool first = header_allowed;
    header_allowed = false;
    if (text_fields == 0) {
      rows.push_back(std::move(row));
    } else if (first && text_fields == 1 && std::isnan(row.values[0]) && row.values.size() > 1) {
      row.header = true;  // a corner label, then numbers
      rows.push_back(std::move(row));
    } else if (!first) {
      throw InputError(path + ":" + std::to_string(line_number) + ": expected " + expected + ", found '" +
                       Excerpt(text) + "'");
    }  // else a header of text: skipped
  }
  return rows;
}

void ReadTableCsv(const std::string& text, const std::string& path, std::vector<double>* times,
                  std::vector<double>* values, const std::string& x) {
  int previous_line = 0;
  const std::string expected = "two numbers (" + x + ", y)";
  for (const NumberRow& row : ReadNumberRows(text, path, expected)) {
    const std::string where = path + ":" + std::to_string(row.line);
    if (row.header) continue;  // a header such as "time, 0.5": not a point
    if (row.values.size() != 2)
      throw InputError(where + ": expected " + expected + ", found " + std::to_string(row.values.size()));
    CheckPoint(row.values[0], row.values[1], *times, where, "line " + std::to_string(previous_line), x);
    times->push_back(row.values[0]);
    values->push_back(row.values[1]);
    previous_line = row.line;
  }
  CheckCount(*times, path);
}

}  // namespace mechflow::blocks
