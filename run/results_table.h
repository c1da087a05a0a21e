#pragma once
// Reading back a results CSV (as `mechflow run` writes it, or any CSV with a
// header line and time in its first column): `mechflow psd` takes its
// signals from one, `mechflow fit` its measurements.

#include <string>
#include <vector>

namespace mechflow::run {

struct ResultsColumns {
  std::vector<double> time;                 // the first column, strictly rising
  std::vector<std::vector<double>> values;  // one per wanted column, in the order asked
  std::vector<int> lines;                   // each row's line in the file (from 2; blank lines skipped)
};

// The time column and the columns named `wanted` of a CSV file's `text`
// (`path` names it in messages). Fields follow RFC 4180 ("..." may hold
// commas); a byte-order mark is ignored; every field read must be a whole
// finite number. InputError naming path:line for a bad row, a time not after
// the one before, or a missing column (with the columns there are).
ResultsColumns ReadResultsColumns(const std::string& text, const std::string& path,
                                  const std::vector<std::string>& wanted);

}  // namespace mechflow::run
