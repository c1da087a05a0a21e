#pragma once
// Force analysis (the seed's "Analysis of force elements",
// docs/ELEMENTS.md 3.10): one force element of a diagram, detached and
// driven along its own coordinate as x = x0 + a sin(2 pi f t)
// (analysis/element_drive_block.h), for every combination of varied
// identifier values, amplitudes and frequencies.
//
// Each case runs `cycles` periods with `samples` rows per period (the drive
// starts half a row into its sine, so turning points fall between rows),
// then:
//   - periodic: the reaction over the last period differs from the one
//     before it by at most 1e-6 of its largest value (else the case is
//     marked not periodic, with the difference, and its figures still given);
//   - the first harmonic of the reaction R = -F over the last period,
//     R ~ R_s sin(w t) + R_c cos(w t) (sums over the rows, exact for
//     periodic band-limited signals): dynamic stiffness K = |R1| / a, phase
//     delta = atan2(R_c, R_s) (the force's lead over the displacement),
//     force amplitude |R1|;
//   - the loop energy, the work done on the element over the period,
//     oint R dx = integral of R v dt (what it dissipates per cycle);
//   - the loop itself: x', v and R at every row of the last period.
// A case whose rows or figures are not finite numbers (an amplitude the
// element's geometry or force law cannot represent) fails, saying so; it is
// never marked periodic.

#include <string>
#include <utility>
#include <vector>

#include "analysis/interrupted.h"
#include "diagrams/loader.h"

namespace mechflow::analysis {

struct ForceAnalysisRequest {
  std::string file;
  diagrams::LoadOptions options;  // variants, --set, unsafe Lua
  std::string element;            // its name
  std::string component;          // a bushing's dx ... az; else empty
  std::vector<double> amplitudes, frequencies;
  // varied identifiers: each entry sets every one of its names to each value
  std::vector<std::pair<std::vector<std::string>, std::vector<double>>> vary;
  int cycles = 10;    // >= 2
  int samples = 1000; // rows per period, >= 16; cycles x samples <= 10^7 (kept in memory)
  CancelFlag interrupt = nullptr;  // set: the case under way ends, no more start
};

struct ForceAnalysisCase {
  std::vector<double> varied;  // one value per vary entry
  double amplitude = 0.0, frequency = 0.0;
  double stiffness = 0.0;      // K = |R1| / a
  double phase = 0.0;          // delta [rad]
  double force_amplitude = 0.0;
  double loop_energy = 0.0;    // [J] (or N m rad)
  double x0 = 0.0;             // the coordinate the drive oscillates about
  bool periodic = false;
  double periodic_error = 0.0; // largest difference of the last two periods, relative
  std::string failure;         // the run failed: why (figures are then zero)
  std::vector<double> x, v, reaction;  // the last period, samples + 1 rows
};

struct ForceAnalysis {
  std::string diagram;       // the diagram's name
  std::string element_what;  // "element 'NAME'" (and component)
  std::vector<ForceAnalysisCase> cases;  // varied values, then amplitude, then frequency (fastest)
  std::size_t planned = 0;   // cases asked for; more than cases.size() when interrupted
  int interrupted = 0;       // the signal that stopped it (request.interrupt), else 0
};

// Throws InputError for bad requests (no such element, an element that
// cannot be driven, a frequency or amplitude that is not positive or whose
// motion overflows, an unknown varied identifier). When request.interrupt is
// set the analysis returns the cases finished before, with `interrupted`.
ForceAnalysis RunForceAnalysis(const ForceAnalysisRequest& request);

// The first harmonic of `values`, N samples over exactly one period, the
// first at phase `phase0`: {R_s, R_c} of R_s sin + R_c cos of the phase.
std::pair<double, double> FirstHarmonic(const std::vector<double>& values, double phase0 = 0.0);

}  // namespace mechflow::analysis
