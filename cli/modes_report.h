#pragma once
// Output of `mechflow modes`: a table on the terminal and NAME.modes.csv.

#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "analysis/modes.h"

namespace mechflow::cli {

// Everything one linear analysis found, as the report shows it.
using ModesReport = analysis::ModesAnalysis;

// Prints where the diagram was linearised (state values and roles), the modes
// sorted by natural frequency (f damped and undamped [Hz], damping ratio,
// lambda [rad/s], what kind of mode: real modes with their decay rate and time
// constant), then the mode shapes as a table of states by modes.
void PrintModes(const ModesReport& report, std::ostream& out);

// Columns: mode (1-based index), frequency_hz (damped, |Im lambda| / 2 pi),
// natural_frequency_hz (|lambda| / 2 pi), damping_ratio, lambda_re [1/s],
// lambda_im [rad/s], then one per state with the mode shape (real part).
// Numbers at full precision.
void WriteModesCsv(const std::vector<analysis::Mode>& modes, const std::vector<std::string>& states,
                   std::ostream& csv);

}  // namespace mechflow::cli
