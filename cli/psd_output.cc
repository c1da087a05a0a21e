#include "cli/psd_output.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "blocks/outputs/csv.h"
#include "blocks/support/message_number.h"
#include "cli/plot.h"
#include "cli/xy_plot.h"
#include "mech/errors.h"

namespace mechflow::cli {
namespace {

using blocks::MessageNumber;

// The rows from `from` on, on a uniform grid: as they are when their steps
// agree to 1e-6, else linearly interpolated at the mean step (an event can
// put an extra row between two grid rows).
std::vector<std::vector<double>> UniformRows(const PsdRequest& r, double* dt) {
  std::size_t first = 0;
  while (first < r.time.size() && r.time[first] < r.from) ++first;
  const std::size_t n = r.time.size() - first;
  if (n < 16)
    throw InputError("spectrum: " + std::to_string(n) + " rows from t = " + MessageNumber(std::max(r.from, 0.0)) +
                     " s on; at least 16 are needed");
  const double t0 = r.time[first], t1 = r.time.back();
  *dt = (t1 - t0) / (n - 1);
  if (!(*dt > 0.0)) throw InputError("spectrum: the rows' times do not advance");
  bool uniform = true;
  for (std::size_t k = first + 1; k < r.time.size(); ++k) {
    if (!(r.time[k] > r.time[k - 1]))  // interpolating rows out of order would make up a signal
      throw InputError("spectrum: the row at t = " + MessageNumber(r.time[k]) + " s is not after the one before (t = " +
                       MessageNumber(r.time[k - 1]) + " s); the rows must be in rising time order");
    uniform = uniform && std::abs(r.time[k] - r.time[k - 1] - *dt) <= 1e-6 * *dt;
  }
  std::vector<std::vector<double>> out;
  for (const PsdSignal& s : r.signals) {
    std::vector<double> v;
    if (uniform) {
      v.assign(s.values.begin() + first, s.values.end());
    } else {
      std::size_t j = first;
      for (std::size_t k = 0; k < n; ++k) {
        const double t = t0 + k * *dt;
        while (j + 2 < r.time.size() && r.time[j + 1] <= t) ++j;
        const double span = r.time[j + 1] - r.time[j];
        const double u = span > 0 ? (t - r.time[j]) / span : 0.0;
        v.push_back(s.values[j] + u * (s.values[j + 1] - s.values[j]));
      }
    }
    out.push_back(std::move(v));
  }
  return out;
}

}  // namespace

std::string WritePsd(const PsdRequest& request, const OutputFolder& folder, std::ostream& out) {
  double dt = 0.0;
  const auto rows = UniformRows(request, &dt);
  std::vector<analysis::Spectrum> spectra;
  for (const auto& v : rows) spectra.push_back(analysis::WelchPsd(v, dt, request.options));
  const analysis::Spectrum& first = spectra.front();
  out << "power spectral density (Welch: " << first.segment
      << " samples per segment = " << MessageNumber(first.segment * dt) << " s, " << first.segments
      << " segments overlapping by " << MessageNumber(request.options.overlap * 100) << " %, "
      << (request.options.window == analysis::Window::kHann ? "Hann" : "rectangular")
      << " window, one-sided, mean removed; resolution " << MessageNumber(first.resolution) << " Hz)\n";
  std::ostringstream csv;
  csv << "frequency [Hz]";
  for (const PsdSignal& s : request.signals) csv << "," << blocks::CsvField("PSD " + s.name + " [signal^2/Hz]");
  csv << "\n";
  for (std::size_t k = 0; k < first.frequency.size(); ++k) {
    csv << blocks::CsvNumber(first.frequency[k]);
    for (const auto& s : spectra) csv << "," << blocks::CsvNumber(s.density[k]);
    csv << "\n";
  }
  for (std::size_t i = 0; i < spectra.size(); ++i) {
    out << request.signals[i].name << ": peaks (frequency [Hz], level [signal^2/Hz])";
    for (const analysis::SpectralPeak& p : analysis::FindPeaks(spectra[i], request.peaks))
      out << "  " << MessageNumber(p.frequency) << " " << MessageNumber(p.level);
    out << "\n";
  }
  const std::string csv_name = request.stem + ".psd.csv", plot = request.stem + ".psd.png";
  folder.Write(csv_name, csv.str());
  out << "wrote " << folder.PathOf(csv_name) << "\n";
  if (!request.plot) return "";
  XYPanel panel{"power spectral density", "frequency [Hz]", "PSD [signal^2/Hz]", {}, false, true,
                request.max_frequency};
  for (std::size_t i = 0; i < request.signals.size(); ++i)
    panel.curves.push_back({0, static_cast<int>(i) + 1, request.signals[i].name});
  const std::string warning = DrawPlot(XYPlotScript({panel}, request.title, csv_name, plot), folder, plot);
  if (warning.empty()) out << "wrote " << folder.PathOf(plot) << "\n";
  return warning;
}

}  // namespace mechflow::cli
