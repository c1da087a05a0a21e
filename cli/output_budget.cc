#include "cli/output_budget.h"

#include <charconv>
#include <cmath>
#include <cstdio>

#include "cli/arguments.h"
#include "mech/errors.h"

namespace mechflow::cli {

std::uint64_t ParseByteSize(const std::string& text, const std::string& option) {
  const auto bad = [&] {
    return UsageError(option + ": '" + text + "' is not a size; give bytes with an optional K, M, G or T (binary: " +
                      "1K = 1024), e.g. 8G");
  };
  double number = 0.0;
  const char* const end = text.data() + text.size();
  const auto [rest, error] = std::from_chars(text.data(), end, number, std::chars_format::fixed);
  if (text.empty() || error != std::errc() || !std::isfinite(number)) throw bad();
  int shift = 0;
  if (rest != end) {
    if (rest + 1 != end) throw bad();
    switch (*rest) {
      case 'K': case 'k': shift = 10; break;
      case 'M': case 'm': shift = 20; break;
      case 'G': case 'g': shift = 30; break;
      case 'T': case 't': shift = 40; break;
      default: throw bad();
    }
  }
  const double bytes = std::floor(std::ldexp(number, shift));
  if (!(bytes >= 1.0)) throw UsageError(option + ": '" + text + "' is less than a byte; give a size from 1, e.g. 8G");
  if (!(bytes <= 0x1p63)) throw UsageError(option + ": '" + text + "' is more than 8388608T");
  return static_cast<std::uint64_t>(bytes);
}

std::string ByteSizeText(double bytes) {
  static const char* const kUnits[] = {"bytes", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  int unit = 0;
  while (bytes >= 1024.0 && unit < 6) bytes /= 1024.0, ++unit;
  char text[64];
  std::snprintf(text, sizeof text, unit == 0 ? "%.0f %s" : "%.3g %s", bytes, kUnits[unit]);
  return text;
}

OutputEstimate EstimateResultsCsv(const blocks::SolverOptions& solver, int columns, const std::string& file) {
  const double interval =
      solver.output_interval > 0 ? solver.output_interval : (solver.t_end - solver.t_start) / 1000.0;
  const double rows = std::floor((solver.t_end - solver.t_start) / interval) + 1.0;
  char reckoning[160];
  std::snprintf(reckoning, sizeof reckoning, "%.0f rows x %d columns x %.0f bytes", rows, columns, kCsvBytesPerValue);
  return {file, rows * columns * kCsvBytesPerValue, rows, reckoning,
          "raise the output interval, shorten t_end, log fewer signals, or raise the budget with --max-output 8G"};
}

void RefuseOverBudget(const OutputEstimate& estimate, std::uint64_t budget) {
  if (estimate.bytes <= static_cast<double>(budget)) return;
  throw InputError(estimate.file + " would be about " + ByteSizeText(estimate.bytes) + " (" + estimate.reckoning +
                   "), past the budget of " + ByteSizeText(static_cast<double>(budget)) + " per output file; " +
                   estimate.advice);
}

}  // namespace mechflow::cli
