#include "analysis/spectrum.h"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>

#include "blocks/support/message_number.h"
#include "mech/errors.h"

namespace mechflow::analysis {
namespace {

using blocks::MessageNumber;

struct PlanDeleter {
  void operator()(fftw_plan_s* p) const { fftw_destroy_plan(p); }
};

}  // namespace

Window ParseWindow(const std::string& name, const std::string& where) {
  if (name == "hann") return Window::kHann;
  if (name == "rectangular") return Window::kRectangular;
  throw InputError(where + ": unknown window '" + name + "'; expected hann or rectangular");
}

Spectrum WelchPsd(const std::vector<double>& samples, double dt, const WelchOptions& options) {
  const int n = static_cast<int>(samples.size());
  if (!(dt > 0.0) || !std::isfinite(dt)) throw InputError("spectrum: the sampling interval must be > 0");
  if (!(options.overlap >= 0.0 && options.overlap <= kMaxOverlap))
    throw InputError("spectrum: overlap " + MessageNumber(options.overlap) + " is not from 0 to " +
                     MessageNumber(kMaxOverlap) +
                     " (each sample is transformed about 1 / (1 - overlap) times); 0.5 is usual");
  int segment = options.segment;
  if (segment == 0) {
    segment = 16;
    while (segment * 2 <= n / 4) segment *= 2;
  }
  if (segment < 16) throw InputError("spectrum: a segment needs at least 16 samples");
  if (n < segment)
    throw InputError("spectrum: " + std::to_string(n) + " samples are fewer than one segment of " +
                     std::to_string(segment) + " (log more rows, or shorten the segment)");
  for (double s : samples)
    if (!std::isfinite(s)) throw InputError("spectrum: the signal holds a value that is not a number");
  const int step = std::max(1, static_cast<int>(std::lround(segment * (1.0 - options.overlap))));
  const int segments = (n - segment) / step + 1;
  if (double(segments) * segment > double(kMaxCoverage) * n)
    throw InputError("spectrum: " + std::to_string(segments) + " segments of " + std::to_string(segment) +
                     " samples (overlap " + MessageNumber(options.overlap) + ") would transform the " +
                     std::to_string(n) + " samples more than " + std::to_string(kMaxCoverage) +
                     " times over; lower the overlap (0.5 is usual) or lengthen the segment");

  double mean = 0.0;
  for (double s : samples) mean += s;
  mean /= n;
  std::vector<double> window(segment, 1.0);
  if (options.window == Window::kHann)
    for (int k = 0; k < segment; ++k)
      window[k] = 0.5 - 0.5 * std::cos(2 * std::numbers::pi * k / segment);  // periodic Hann
  double power = 0.0;
  for (double w : window) power += w * w;

  const int bins = segment / 2 + 1;
  std::vector<double> in(segment);
  std::vector<fftw_complex> out(bins);
  const std::unique_ptr<fftw_plan_s, PlanDeleter> plan(
      fftw_plan_dft_r2c_1d(segment, in.data(), out.data(), FFTW_ESTIMATE));
  Spectrum s;
  s.segment = segment;
  s.resolution = 1.0 / (segment * dt);
  s.density.assign(bins, 0.0);
  for (int start = 0; start + segment <= n; start += step) {
    StopIfInterrupted(options.interrupt);
    for (int k = 0; k < segment; ++k) in[k] = (samples[start + k] - mean) * window[k];
    fftw_execute(plan.get());
    for (int k = 0; k < bins; ++k) s.density[k] += out[k][0] * out[k][0] + out[k][1] * out[k][1];
    ++s.segments;
  }
  const double fs = 1.0 / dt;
  for (int k = 0; k < bins; ++k) {
    const bool edge = k == 0 || (segment % 2 == 0 && k == bins - 1);
    s.density[k] *= (edge ? 1.0 : 2.0) / (fs * power * s.segments);
    s.frequency.push_back(k * s.resolution);
  }
  return s;
}

std::vector<SpectralPeak> FindPeaks(const Spectrum& spectrum, int count, double floor) {
  if (count < 0) throw InputError("spectrum: the number of peaks must be 0 or more, not " + std::to_string(count));
  const auto& p = spectrum.density;
  const double largest = p.empty() ? 0.0 : *std::max_element(p.begin(), p.end());
  std::vector<SpectralPeak> peaks;
  for (std::size_t k = 1; k + 1 < p.size(); ++k) {
    if (!(p[k] > p[k - 1] && p[k] >= p[k + 1] && p[k] > floor * largest)) continue;
    // parabola through the log levels of the three bins
    const double a = std::log(p[k - 1]), b = std::log(p[k]), c = std::log(p[k + 1]);
    const double curvature = a - 2 * b + c;
    const double shift = curvature < 0 ? 0.5 * (a - c) / curvature : 0.0;
    peaks.push_back({spectrum.frequency[k] + shift * spectrum.resolution,
                     std::exp(b - 0.25 * (a - c) * shift)});
  }
  std::sort(peaks.begin(), peaks.end(), [](const auto& x, const auto& y) { return x.level > y.level; });
  if (static_cast<int>(peaks.size()) > count) peaks.resize(count);
  return peaks;
}

}  // namespace mechflow::analysis
