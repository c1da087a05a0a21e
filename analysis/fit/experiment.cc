#include "analysis/fit/experiment.h"

#include <charconv>
#include <cmath>

#include "blocks/outputs/csv.h"
#include "blocks/support/excerpt.h"
#include "mech/errors.h"
#include "run/results_table.h"

namespace mechflow::analysis::fit {

Match ParseMatch(const std::string& text) {
  const auto eq = text.find('=');
  const std::string usage = "; expected SIGNAL=COLUMN or SIGNAL=COLUMN:WEIGHT (block.port=column of the data)";
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
    throw InputError("--match '" + blocks::Excerpt(text) + "'" + usage);
  Match m;
  m.signal = text.substr(0, eq);
  m.column = text.substr(eq + 1);
  if (const auto colon = m.column.rfind(':'); colon != std::string::npos) {
    const std::string w = m.column.substr(colon + 1);
    m.column = m.column.substr(0, colon);
    const auto [end, error] = std::from_chars(w.data(), w.data() + w.size(), m.weight);
    if (w.empty() || error != std::errc() || end != w.data() + w.size() || !std::isfinite(m.weight) ||
        !(m.weight > 0))
      throw InputError("--match " + blocks::Excerpt(text) + ": the weight '" + blocks::Excerpt(w) +
                       "' is not a number > 0");
    if (m.column.empty()) throw InputError("--match '" + blocks::Excerpt(text) + "'" + usage);
  }
  for (const auto& [prefix, kind] : {std::pair<std::string, Match::Kind>{"report:", Match::Kind::kFigureValue},
                                     {"report-time:", Match::Kind::kFigureTime}}) {
    if (m.signal.rfind(prefix, 0) == 0) {
      m.kind = kind;
      m.figure = m.signal.substr(prefix.size());
      if (m.figure.empty()) throw InputError("--match '" + blocks::Excerpt(text) + "': " + prefix + " needs a <report> label");
    }
  }
  return m;
}

Experiment ReadExperiment(const std::string& text, const std::string& path, const std::vector<Match>& matches) {
  std::vector<std::string> columns;
  for (const Match& m : matches) columns.push_back(m.column);
  run::ResultsColumns table = run::ReadResultsColumns(text, path, columns);
  if (table.time.empty()) throw InputError(path + ": no rows of measurements after the header");
  Experiment e;
  e.file = path;
  e.times = std::move(table.time);
  e.measured = std::move(table.values);
  e.lines = std::move(table.lines);
  // a figure is one number per experiment: its column holds it in every row
  for (std::size_t k = 0; k < matches.size(); ++k) {
    if (matches[k].is_signal()) continue;
    for (std::size_t i = 1; i < e.times.size(); ++i)
      if (e.measured[k][i] != e.measured[k][0])
        throw InputError(path + ":" + std::to_string(e.lines[i]) + ": " + matches[k].column + " is " +
                         blocks::CsvNumber(e.measured[k][i]) + ", not " + blocks::CsvNumber(e.measured[k][0]) +
                         " as in the first row; it is matched to the figure '" + matches[k].figure +
                         "', one number per data file (give it one row, or the same value in every row)");
    e.measured[k].resize(1);
  }
  return e;
}

void CheckTimesInRun(const Experiment& experiment, double t_start, double t_end) {
  for (std::size_t i = 0; i < experiment.times.size(); ++i) {
    const double t = experiment.times[i];
    if (t < t_start || t > t_end)
      throw InputError(experiment.file + ":" + std::to_string(experiment.lines.at(i)) + ": time " + blocks::CsvNumber(t) +
                       " is outside the run (" + blocks::CsvNumber(t_start) + " to " + blocks::CsvNumber(t_end) +
                       " s); drop the row, or run longer (--t-end)");
  }
}

}  // namespace mechflow::analysis::fit
