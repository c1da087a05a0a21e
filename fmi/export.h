#pragma once
// export-fmu: a diagram packed as an FMI 2.0 co-simulation FMU.
//
//   NAME.fmu
//     modelDescription.xml        fmi/model_description.h
//     binaries/linux64/ID.so      the FMU's code (fmi/fmi2_functions.cc) and,
//                                 beside it, the shared libraries it needs that
//                                 Debian's base system lacks (found through
//                                 RUNPATH $ORIGIN)
//     resources/DIAGRAM.xml       the diagram, as it was
//     resources/PATH              every file it reads (tables, scripts,
//                                 subsystems, parts, mechanisms, and the files
//                                 those read), by its path from the diagram's
//                                 folder, or from the folder holding them all
//                                 when --allow-read or --library reach outside
//                                 it (the diagram is then resources/SUB/DIAGRAM.xml)
//     resources/mechflow.txt      variants and --set values (fmi/packed_settings.h)
//     resources/udunits/          the units database
//
// The files are those the loader read (blocks::ReadPolicy keeps them), not
// found by reading the XML again. The FMU loads the diagram with reading
// allowed in its resources folder only; export-fmu loads the packed copy so
// first and refuses a diagram that fails there (a file named by an absolute
// path), as it refuses anything that would loosen the Lua sandbox.

#include <string>
#include <utility>
#include <vector>

namespace mechflow::fmi {

struct ExportRequest {
  std::string diagram;  // the diagram file
  std::vector<std::string> variants;
  std::vector<std::pair<std::string, double>> overrides;
  std::vector<std::pair<std::string, std::string>> expression_overrides;
  std::string folder;   // where to write NAME.fmu (NAME: the diagram's name); it exists
  std::string runtime;  // the folder with linux64/ (the FMU's binaries) and udunits/
  std::vector<std::string> allow_read, library;  // --allow-read and --library, as for mechflow run
};

struct ExportSummary {
  std::string fmu;  // the file written, FOLDER/NAME.fmu
  std::string model_identifier, guid;
  int files = 0;    // files packed besides the diagram
  int outputs = 0, inputs = 0, parameters = 0;
  std::vector<std::string> binaries;  // the file names in binaries/linux64/
  // what the diagram asks for that an FMU does not do (it writes no file):
  // "FILE:LINE: <output plot>", one each
  std::vector<std::string> left_out;
};

// Throws InputError (file:line) for a diagram it cannot export, std::runtime_error
// when the FMU cannot be written.
ExportSummary ExportFmu(const ExportRequest& request);

// The runtime folder beside the running program (PROGRAM_DIR/fmu).
std::string DefaultRuntimeFolder();

}  // namespace mechflow::fmi
