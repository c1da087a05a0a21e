#include "cli/export_fmu_command.h"

#include <filesystem>

#include "cli/output_folder.h"
#include "fmi/export.h"
#include "mech/errors.h"

namespace mechflow::cli {

std::string ExportFmuHelp() {
  return "usage: mechflow export-fmu FILE --out DIR [--variant NAME] [--set NAME=VALUE]...\n"
         "       [--allow-read DIR] [--library DIR]\n"
         "\n"
         "Writes the diagram as an FMI 2.0 co-simulation FMU for Linux x86-64, to be run\n"
         "by another tool: DIR/NAME.fmu, NAME being the diagram's name (<diagram name>,\n"
         "else its file name without .xml), as mechflow run names its results. Its\n"
         "<log>ged signals are the outputs, its top-level <input>s the inputs (held\n"
         "over each communication step), its identifiers defined by numbers the\n"
         "parameters (fixed: set before the run starts), its <solver> and <output\n"
         "interval> the default experiment. The FMU carries the diagram, every file it\n"
         "reads (tables, scripts, mechanisms, subsystems, parts, by their paths from\n"
         "the diagram's folder, or from the folder holding them all when --allow-read\n"
         "or --library reach outside it), the shared libraries it needs and the units\n"
         "database; it runs the diagram with the Lua sandbox on, reading files from\n"
         "the FMU only, and writes no file (the diagram's <output> files, <report>s,\n"
         "<spectrum>s and <xy> panels are left out, each noted). --variant, --set,\n"
         "--allow-read and --library are applied as in mechflow run and packed into\n"
         "the FMU (its parameters start there).\n"
         "\n"
         "  --out DIR  the folder to write NAME.fmu into (required; made if needed)\n"
         "\n"
         "Refused: a diagram that names a file by an absolute path (name it relative\n"
         "to the file that names it), --unsafe-lua, and --t-end (the importer gives\n"
         "the stop time).\n"
         "\n"
         "Example: mechflow export-fmu diagrams/examples/cart_pendulum_friction.xml --out fmu\n"
         "         (writes fmu/cart_pendulum_friction.fmu)\n"
         "\n"
         "Exit codes: 0 written, 1 the FMU could not be written, 2 bad input.\n";
}

int ExportFmuCommand(const Arguments& args, std::ostream& out, std::ostream& err) {
  namespace fs = std::filesystem;
  const std::string what = "(NAME: the diagram's name)";
  if (!args.out_given) throw UsageError("needs --out DIR, the folder to write NAME.fmu into " + what);
  std::error_code ignored;
  if (fs::exists(args.out_dir, ignored) && !fs::is_directory(args.out_dir, ignored))
    throw UsageError("--out '" + args.out_dir + "' is a file; --out names the folder to write NAME.fmu into " + what);
  if (fs::path(args.out_dir).extension() == ".fmu" && !fs::exists(args.out_dir, ignored))
    throw UsageError("--out '" + args.out_dir + "': --out names the folder to write NAME.fmu into " + what +
                     ", not the file; give the folder");
  if (args.t_end)
    throw UsageError("--t-end: the importer gives the stop time (fmi2SetupExperiment); the diagram's <solver "
                     "t_end> is only the FMU's default experiment");
  if (args.unsafe_lua) throw UsageError("--unsafe-lua: an FMU runs its diagram with the Lua sandbox on");
  const OutputFolder folder(args.out_dir);  // made as mechflow run makes it
  const fmi::ExportRequest request{args.file,    args.variants,  args.overrides, args.set_expressions,
                                   folder.path(), fmi::DefaultRuntimeFolder(), args.allow_read, args.library};
  fmi::ExportSummary s;
  try {
    s = fmi::ExportFmu(request);
  } catch (const InputError&) {
    throw;
  } catch (const std::runtime_error& e) {
    err << "mechflow export-fmu: " << e.what() << "\n";
    return 1;
  }
  out << "wrote " << s.fmu << ": FMI 2.0 co-simulation, model identifier " << s.model_identifier << ", "
      << s.outputs << " output(s), " << s.inputs << " input(s), " << s.parameters << " parameter(s); "
      << s.files << " file(s) the diagram reads in resources/, " << s.binaries.size()
      << " file(s) in binaries/linux64\n";
  // no silent no-op: what the diagram asks for and the FMU does not do
  for (const std::string& item : s.left_out) out << "note: " << item << " is left out: an FMU writes no file\n";
  return 0;
}

}  // namespace mechflow::cli
