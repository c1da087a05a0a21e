#pragma once
// The files of a power spectral density (analysis/spectrum.h), written for
// `mechflow psd` and for a diagram's <spectrum> outputs: STEM.psd.csv
// (frequency, then a density column per signal), the plot STEM.psd.png (log
// scale) and the peaks printed.

#include <ostream>
#include <string>
#include <vector>

#include "analysis/spectrum.h"
#include "cli/output_folder.h"

namespace mechflow::cli {

struct PsdSignal {
  std::string name;
  std::vector<double> values;
};

struct PsdRequest {
  std::vector<double> time;        // the rows' times, rising (uniform; else resampled)
  std::vector<PsdSignal> signals;
  analysis::WelchOptions options;
  double from = -1e300;            // rows before this time are left out [s]
  int peaks = 5;                   // listed per signal
  double max_frequency = 0.0;      // > 0: the plot ends there (the CSV goes to fs/2) [Hz]
  std::string stem, title;         // file names STEM.psd.*; the plot's title
  bool plot = true;                // false: the CSV only (run --no-plot)
};

// Throws InputError (bad options, too few rows, times out of order) and
// WriteError; analysis::Interrupted when request.options.interrupt is set
// while the spectra are computed (before anything is written). Returns the
// plot warning ("" when the plot was drawn or not asked for).
std::string WritePsd(const PsdRequest& request, const OutputFolder& folder, std::ostream& out);

}  // namespace mechflow::cli
