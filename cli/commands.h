#pragma once
// The mechflow commands. Each returns the process exit code:
// 0 ok, 1 simulation failed, 2 bad input.

#include <ostream>

#include "cli/arguments.h"

namespace mechflow::cli {

int RunCommand(const Arguments& args, std::ostream& out, std::ostream& err);
int CheckCommand(const Arguments& args, std::ostream& out, std::ostream& err);
int GraphCommand(const Arguments& args, std::ostream& out, std::ostream& err);
int ModesCommand(const Arguments& args, std::ostream& out, std::ostream& err);

// Parses `argv` and dispatches; catches every error and maps it to an exit code.
int Main(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

}  // namespace mechflow::cli
