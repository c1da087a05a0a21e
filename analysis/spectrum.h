#pragma once
// Power spectral density by Welch's method (the seed's
// §7.9, Fig. 7.26), with FFTW for the transforms.
//
// The signal (uniformly sampled, interval dt) has its mean removed and is cut
// into segments of `segment` samples overlapping by `overlap` (a fraction);
// each is multiplied by the window (Hann by default) and transformed; the
// squared magnitudes are averaged and scaled to a one-sided density in
// signal^2/Hz:
//   P(f_k) = c_k |X_k|^2 / (fs * sum w^2),  c_k = 2 except at 0 and fs/2,
// so that sum_k P(f_k) * df equals the signal's variance (Parseval) for
// the rectangular window, and its windowed estimate otherwise.
//
// The work is bounded by the data (analysis/spectrum_limits.h), and a
// Ctrl-C stops it between two segments.

#include <string>
#include <vector>

#include "analysis/interrupted.h"
#include "analysis/spectrum_limits.h"

namespace mechflow::analysis {

enum class Window { kHann, kRectangular };

struct WelchOptions {
  int segment = 0;       // samples per segment; 0: the largest power of two <= n / 4 (at least 16)
  double overlap = 0.5;  // [0, kMaxOverlap]
  Window window = Window::kHann;
  CancelFlag interrupt = nullptr;  // looked at before every segment's transform
};

struct Spectrum {
  std::vector<double> frequency;  // [Hz], 0 .. fs/2 in steps of fs / segment
  std::vector<double> density;    // [signal^2/Hz]
  int segment = 0, segments = 0;  // what was used
  double resolution = 0.0;        // df [Hz]
};

// Throws InputError when the options are bad, the work would exceed the
// bound of analysis/spectrum_limits.h, or the signal has fewer samples than
// one segment (or fewer than 16); Interrupted when options.interrupt is set.
Spectrum WelchPsd(const std::vector<double>& samples, double dt, const WelchOptions& options);

struct SpectralPeak {
  double frequency = 0.0, level = 0.0;
};
// Local maxima of the density (above both neighbours and above `floor` times
// the largest), strongest first, at most `count` (>= 0, else InputError);
// each refined by a parabola through its bin and the two beside it.
std::vector<SpectralPeak> FindPeaks(const Spectrum& spectrum, int count, double floor = 1e-6);

// "hann" or "rectangular"; throws InputError naming `where` otherwise.
Window ParseWindow(const std::string& name, const std::string& where);

}  // namespace mechflow::analysis
