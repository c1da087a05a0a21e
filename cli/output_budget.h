#pragma once
// Output budgets: every large file a run writes (the results CSV, the
// animation NAME.html and NAME.glb) is estimated before the run and refused
// past a budget per file (--max-output, default 1 GiB, 256 MiB for the
// animation), so that a small
// diagram cannot fill a disk; and the results file stops at the budget if
// the run makes more rows than estimated (rows at events).

#include <cstdint>
#include <optional>
#include <string>

#include "diagrams/loader.h"

namespace mechflow::cli {

inline constexpr std::uint64_t kDefaultMaxOutputBytes = std::uint64_t{1} << 30;  // 1 GiB per file
// The animation's page and glTF by default: a browser or viewer that must
// hold the whole file in memory gives up long before 1 GiB.
inline constexpr std::uint64_t kDefaultMaxAnimationBytes = std::uint64_t{256} << 20;

// Bytes per value of the results CSV: a shortest round-trip number and its
// separator. Measured: 11.6 to 15.9 bytes in the examples' results
// (pendulum_chain, four_bar, damping_ratio), 17.3 over 40000 s of
// damping_ratio; a number of 17 significant digits and an exponent takes 24.
// Rows past the estimate stop at the budget (ResultsFile::SetByteLimit).
inline constexpr double kCsvBytesPerValue = 20.0;

// "8G", "512M", "100000": bytes with an optional K, M, G or T suffix (binary
// multiples: 1K = 1024). UsageError naming `option` otherwise.
std::uint64_t ParseByteSize(const std::string& text, const std::string& option);

// "3.5 GiB", "840 MiB", "12 KiB", "900 bytes".
std::string ByteSizeText(double bytes);

// The size a file of a run is expected to reach, and how the estimate came.
struct OutputEstimate {
  std::string file;     // as named in the output folder
  double bytes = 0.0;
  double rows = 0.0;        // the results CSV: its rows
  std::string reckoning;  // "10000001 rows x 3 columns x 20 bytes"
  std::string advice;     // what makes it smaller
};

// The results CSV: one row per output time from t_start to t_end (rows at
// events come on top), `columns` columns of kCsvBytesPerValue bytes.
OutputEstimate EstimateResultsCsv(const blocks::SolverOptions& solver, int columns, const std::string& file);

// Throws InputError (exit 2) when `estimate` is past `budget`: the file, its
// estimate, the budget, and what to do.
void RefuseOverBudget(const OutputEstimate& estimate, std::uint64_t budget);

}  // namespace mechflow::cli
