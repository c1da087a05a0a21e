#include "cli/export_fmu_command.h"

#include <filesystem>

#include "fmi/export.h"
#include "mech/errors.h"

namespace mechflow::cli {

std::string ExportFmuHelp() {
  return "usage: mechflow export-fmu FILE --out NAME.fmu [--variant NAME] [--set NAME=VALUE]...\n"
         "\n"
         "Writes the diagram as an FMI 2.0 co-simulation FMU for Linux x86-64, to be run\n"
         "by another tool: its <log>ged signals are the outputs, its top-level <input>s\n"
         "the inputs (held over each communication step), its identifiers defined by\n"
         "numbers the parameters (fixed: set before the run starts), its <solver> and\n"
         "<output interval> the default experiment. The FMU carries the diagram file,\n"
         "the shared libraries it needs and the units database; it runs the diagram\n"
         "with the Lua sandbox on and writes no file (the diagram's <output> files,\n"
         "<report>s, <spectrum>s and <xy> panels are left out, each noted). --variant\n"
         "and --set are applied as in mechflow run and packed into the FMU (its\n"
         "parameters start there).\n"
         "\n"
         "  --out NAME.fmu  the file to write (required; its folder must exist)\n"
         "\n"
         "Refused: a diagram that reads another file (tables from CSV, scripts or\n"
         "mechanisms from files, subsystems, parts), --unsafe-lua, --allow-read,\n"
         "--library (the FMU holds the diagram file alone) and --t-end (the importer\n"
         "gives the stop time).\n"
         "\n"
         "Example: mechflow export-fmu diagrams/examples/cart_pendulum_friction.xml --out cart.fmu\n"
         "\n"
         "Exit codes: 0 written, 1 the FMU could not be written, 2 bad input.\n";
}

int ExportFmuCommand(const Arguments& args, std::ostream& out, std::ostream& err) {
  if (!args.out_given)
    throw UsageError("needs --out NAME.fmu, the file to write");
  if (std::filesystem::path(args.out_dir).extension() != ".fmu")
    throw UsageError("--out '" + args.out_dir + "': the FMU's file name ends in .fmu");
  if (args.t_end)
    throw UsageError("--t-end: the importer gives the stop time (fmi2SetupExperiment); the diagram's <solver "
                     "t_end> is only the FMU's default experiment");
  if (args.unsafe_lua) throw UsageError("--unsafe-lua: an FMU runs its diagram with the Lua sandbox on");
  if (!args.allow_read.empty() || !args.library.empty())
    throw UsageError(std::string(args.allow_read.empty() ? "--library" : "--allow-read") +
                     ": the FMU holds the diagram file alone and reads no other");
  const fmi::ExportRequest request{args.file,    args.variants, args.overrides, args.set_expressions,
                                   args.out_dir, fmi::DefaultRuntimeFolder()};
  fmi::ExportSummary s;
  try {
    s = fmi::ExportFmu(request);
  } catch (const InputError&) {
    throw;
  } catch (const std::runtime_error& e) {
    err << "mechflow export-fmu: " << e.what() << "\n";
    return 1;
  }
  out << "wrote " << request.fmu << ": FMI 2.0 co-simulation, model identifier " << s.model_identifier << ", "
      << s.outputs << " output(s), " << s.inputs << " input(s), " << s.parameters << " parameter(s); "
      << s.binaries.size() << " file(s) in binaries/linux64\n";
  // no silent no-op: what the diagram asks for and the FMU does not do
  for (const std::string& item : s.left_out) out << "note: " << item << " is left out: an FMU writes no file\n";
  return 0;
}

}  // namespace mechflow::cli
