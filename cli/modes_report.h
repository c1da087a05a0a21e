#pragma once
// Output of `mechflow modes`: a table on the terminal and modes.csv.

#include <ostream>
#include <string>
#include <vector>

#include "blocks/linearization.h"

namespace mechflow::cli {

void PrintModes(const std::vector<blocks::Mode>& modes, const std::vector<std::string>& states,
                const std::vector<double>& x, bool at_equilibrium, std::ostream& out);
// Columns: mode, frequency_hz, natural_frequency_hz, damping_ratio, lambda_re,
// lambda_im, then one per state with the mode shape (real part).
void WriteModesCsv(const std::vector<blocks::Mode>& modes, const std::vector<std::string>& states,
                   const std::string& path);

}  // namespace mechflow::cli
