#pragma once
// `mechflow force-analysis`: the force analysis of analysis/force_analysis.h
// from the command line -- a table on stdout, CSV files and plots.

#include <ostream>
#include <string>
#include <vector>

#include "cli/arguments.h"

namespace mechflow::cli {

// The options only this command takes (their values in Arguments::command_options).
extern const std::vector<std::string> kForceAnalysisOptions;

std::string ForceAnalysisHelp();

// Exit code: 0 every case periodic, 1 a case failed or did not become
// periodic (everything written), 2 bad input.
int ForceAnalysisCommand(const Arguments& args, std::ostream& out, std::ostream& err);

}  // namespace mechflow::cli
