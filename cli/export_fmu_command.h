#pragma once
// `mechflow export-fmu FILE --out DIR`: the diagram as an FMI 2.0 co-simulation
// FMU, DIR/NAME.fmu (fmi/export.h); this file reads the options and prints
// what was written.

#include <ostream>
#include <string>

#include "cli/arguments.h"

namespace mechflow::cli {

std::string ExportFmuHelp();
int ExportFmuCommand(const Arguments& args, std::ostream& out, std::ostream& err);

}  // namespace mechflow::cli
