#pragma once
// `mechflow psd RESULTS.csv --signal NAME ...`: power spectral densities of
// logged signals from a results file (cli/psd_output.h).

#include <ostream>
#include <string>
#include <vector>

#include "cli/arguments.h"

namespace mechflow::cli {

extern const std::vector<std::string> kPsdOptions;

std::string PsdHelp();

// Exit code: 0 written, 2 bad input (no such signal, too few rows, bad options).
int PsdCommand(const Arguments& args, std::ostream& out, std::ostream& err);

}  // namespace mechflow::cli
