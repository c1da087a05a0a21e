#pragma once
// `mechflow fit`: free parameters of a diagram fitted to measured data
// (analysis/fit/fit.h) from the command line -- the table printed, the
// results, a set file and a plot written.

#include <ostream>
#include <string>
#include <vector>

#include "cli/arguments.h"

namespace mechflow::cli {

// The options only this command takes, in order (their values in
// Arguments::command_options): --variant and --set among them, since after a
// --data they belong to that experiment.
extern const std::vector<std::string> kFitOptions;

std::string FitHelp();

// Exit code: 0 fitted, 1 the fit stopped without converging (everything
// written), 2 bad input, 128 + signal when interrupted.
int FitCommand(const Arguments& args, std::ostream& out, std::ostream& err);

}  // namespace mechflow::cli
