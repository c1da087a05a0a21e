#include "cli/psd_command.h"

#include <cmath>
#include <filesystem>

#include "blocks/support/input_file.h"
#include "cli/interrupt.h"
#include "cli/psd_output.h"
#include "run/results_table.h"
#include "mech/errors.h"

namespace mechflow::cli {

const std::vector<std::string> kPsdOptions = {"--signal", "--segment", "--overlap", "--window",
                                              "--from",   "--peaks",   "--max-frequency"};

std::string PsdHelp() {
  return "usage: mechflow psd RESULTS.csv --signal NAME [--signal NAME]... [--segment N]\n"
         "                  [--overlap F] [--window hann|rectangular] [--from T] [--peaks K]\n"
         "                  [--max-frequency F] [--out DIR]\n"
         "\n"
         "Power spectral density of logged signals in a results file (as mechflow run\n"
         "writes it: time first), by Welch's method: the mean removed, segments of N\n"
         "samples (default: the largest power of two up to a quarter of the rows)\n"
         "overlapping by F (default 0.5), each windowed (default Hann) and transformed by\n"
         "FFTW, their squared magnitudes averaged; one-sided, in signal^2/Hz, so that its\n"
         "integral over frequency is the signal's variance. Rows must be in rising time\n"
         "order and evenly spaced (they are interpolated onto an even grid when not).\n"
         "Writes STEM.psd.csv (frequency, a density per signal) and the plot STEM.psd.png\n"
         "(log scale) into DIR, and prints the K largest peaks of each signal.\n"
         "\n"
         "  --signal NAME   a column of the results (repeatable)\n"
         "  --segment N     samples per segment (at least 16)\n"
         "  --overlap F     overlap of segments, 0 <= F <= 0.99; the segments may cover the\n"
         "                  signal at most 100 times over\n"
         "  --window W      hann or rectangular\n"
         "  --from T        leave out the rows before time T [s] (a start-up transient)\n"
         "  --peaks K       peaks listed per signal (default 5, 0 to 1000)\n"
         "  --max-frequency F  the plot's frequency axis ends at F [Hz] (the CSV goes on)\n"
         "  --out DIR       output folder (created if missing; default: current folder)\n"
         "\n"
         "Example: mechflow run diagrams/examples/frequencies.xml --out results\n"
         "         mechflow psd results/frequencies.csv --signal m.z3 --out results\n"
         "\n"
         "Exit codes: 0 written, 2 bad input (a signal not in the file, too few rows for a\n"
         "segment, rows out of time order, bad options), 130 / 143 ended by SIGINT /\n"
         "SIGTERM (nothing written).\n";
}

int PsdCommand(const Arguments& args, std::ostream& out, std::ostream& err) {
  const InterruptHandlers handlers;  // Ctrl-C, SIGTERM: the transforms stop, nothing is written
  PsdRequest request;
  std::vector<std::string> wanted;
  for (const auto& [option, value] : args.command_options) {
    if (option == "--signal") {
      wanted.push_back(value);
    } else if (option == "--segment") {
      request.options.segment = ParseCount(value, option, 16, 1 << 24);
    } else if (option == "--overlap") {
      request.options.overlap = ParseNumber(value, option);
      if (!(request.options.overlap >= 0 && request.options.overlap <= analysis::kMaxOverlap))
        throw UsageError("--overlap: '" + value + "' is not from 0 to 0.99 (each sample is transformed about " +
                         "1 / (1 - overlap) times); 0.5 is usual");
    } else if (option == "--window") {
      request.options.window = analysis::ParseWindow(value, "--window");
    } else if (option == "--from") {
      request.from = ParseNumber(value, option);
    } else if (option == "--peaks") {
      request.peaks = ParseCount(value, option, 0, 1000);
    } else if (option == "--max-frequency") {
      request.max_frequency = ParseNumber(value, option);
      if (!(request.max_frequency > 0))
        throw UsageError("--max-frequency: '" + value + "' is not a frequency > 0 Hz (leave it out for the whole range)");
    }
  }
  if (wanted.empty()) throw UsageError("needs --signal NAME (a column of " + args.file + ")");
  if (!args.variants.empty() || !args.overrides.empty() || !args.set_expressions.empty() || args.t_end ||
      args.unsafe_lua)
    throw UsageError("reads a results file: --set, --set-file, --variant, --t-end and --unsafe-lua do not apply "
                     "(give them to the run that wrote it)");
  const OutputFolder folder(args.out_dir);
  run::ResultsColumns table = run::ReadResultsColumns(blocks::ReadInputFile(args.file, "results file"), args.file, wanted);
  request.time = std::move(table.time);
  for (std::size_t i = 0; i < wanted.size(); ++i) request.signals.push_back({wanted[i], std::move(table.values[i])});
  request.stem = std::filesystem::path(args.file).stem().string();
  request.title = request.stem;
  request.options.interrupt = InterruptFlag();
  try {
    const std::string warning = WritePsd(request, folder, out);
    if (!warning.empty()) out << "warning: no plot: " << warning << "\n";
  } catch (const analysis::Interrupted& e) {
    err << "mechflow psd: " << e.what() << "; nothing written\n";
    return 128 + e.signal();
  }
  return 0;
}

}  // namespace mechflow::cli
