#pragma once
// Output of `mechflow modes`: a table on the terminal and NAME.modes.csv.

#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "analysis/linearization.h"

namespace mechflow::cli {

// Everything one linear analysis found, as the report shows it.
struct ModesReport {
  double time = 0.0;                                   // [s], where the diagram was linearised
  std::optional<analysis::EquilibriumResult> equilibrium;  // set when linearised at a found equilibrium
  std::vector<std::string> states;                     // "block.state", in state order
  std::vector<double> x;                               // the state linearised at
  analysis::StateRoles roles;                            // coordinates and rates, per state
  std::vector<analysis::Mode> modes;                     // sorted by natural frequency
  std::vector<std::string> switching;                  // analysis::DescribeLinearisedModes
};

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
