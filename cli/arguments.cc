#include "cli/arguments.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

#include "blocks/support/excerpt.h"
#include "blocks/support/input_file.h"
#include "blocks/support/suggest.h"
#include "cli/fit_command.h"
#include "cli/force_analysis_command.h"
#include "cli/help_topics.h"
#include "cli/output_budget.h"
#include "cli/export_fmu_command.h"
#include "cli/psd_command.h"
#include "mech/errors.h"

namespace mechflow::cli {
namespace {

const std::vector<std::string> kCommands = {"run", "check",          "graph", "modes", "sweep",
                                            "force-analysis", "psd", "fit", "export-fmu", "help"};

// The options only `command` takes; their values are its to read.
const std::vector<std::string>& CommandOptions(const std::string& command) {
  static const std::vector<std::string> none;
  if (command == "force-analysis") return kForceAnalysisOptions;
  if (command == "psd") return kPsdOptions;
  if (command == "fit") return kFitOptions;
  return none;
}

// --vary NAME=...: the name and its values.
std::pair<std::string, std::vector<double>> ParseVary(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
    throw UsageError("--vary expects NAME=V1,V2,..., got '" + text + "'");
  const std::string name = text.substr(0, eq);
  return {name, ParseValues(text.substr(eq + 1), "--vary " + name)};
}

// --set NAME=VALUE: a number, or else an expression of identifiers.
void AddSet(const std::string& kv, const std::string& where, Arguments* a) {
  const auto eq = kv.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == kv.size())
    throw UsageError(where + ": expected NAME=VALUE, got '" + blocks::Excerpt(kv) + "'");
  const auto trim = [](std::string s) {
    const auto first = s.find_first_not_of(" \t"), last = s.find_last_not_of(" \t");
    return first == std::string::npos ? std::string() : s.substr(first, last - first + 1);
  };
  const std::string name = trim(kv.substr(0, eq)), text = trim(kv.substr(eq + 1));
  if (name.empty() || text.empty())
    throw UsageError(where + ": expected NAME=VALUE, got '" + blocks::Excerpt(kv) + "'");
  double number = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), number);
  if (error == std::errc() && end == text.data() + text.size() && !std::isfinite(number))
    throw UsageError(where + ": '" + blocks::Excerpt(text) + "' is not a finite number");
  if (error == std::errc() && end == text.data() + text.size()) a->overrides.push_back({name, number});
  else a->set_expressions.push_back({name, text});
}

}  // namespace

double ParseNumber(const std::string& text, const std::string& option) {
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error == std::errc::result_out_of_range)
    throw UsageError(option + ": '" + text + "' is out of the range of a double");
  if (text.empty() || error != std::errc() || end != text.data() + text.size())
    throw UsageError(option + ": '" + text + "' is not a number");
  if (!std::isfinite(value)) throw UsageError(option + ": '" + text + "' is not a finite number");
  return value;
}

int ParseCount(const std::string& text, const std::string& option, int min, int max) {
  long long value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc() || end != text.data() + text.size() || value < min || value > max)
    throw UsageError(option + ": '" + text + "' is not a whole number from " + std::to_string(min) + " to " +
                     std::to_string(max));
  return static_cast<int>(value);
}

std::vector<double> ParseValues(const std::string& spec, const std::string& option) {
  std::vector<std::string> parts;
  const char separator = spec.find(':') != std::string::npos ? ':' : ',';
  for (size_t start = 0;;) {
    const size_t at = spec.find(separator, start);
    parts.push_back(spec.substr(start, at == std::string::npos ? std::string::npos : at - start));
    if (at == std::string::npos) break;
    start = at + 1;
  }
  std::vector<double> values;
  if (separator == ',') {
    for (const std::string& item : parts) values.push_back(ParseNumber(item, option));
    return values;
  }
  // A:B:N (N values evenly spaced) or A:B:N:log (evenly on a log scale)
  const bool log = parts.size() == 4 && parts[3] == "log";
  if (parts.size() != 3 && !log) throw UsageError(option + ": a range is A:B:N or A:B:N:log, got '" + spec + "'");
  const double a = ParseNumber(parts[0], option), b = ParseNumber(parts[1], option);
  const double n = ParseCount(parts[2], option + " (N of A:B:N)", 2, 1000000);
  if (log && !(a > 0 && b > 0)) throw UsageError(option + ": a log range needs A, B > 0");
  for (int i = 0; i < n; ++i) {
    // to 15 digits, so that 0.05:0.2:4 gives 0.15, not 0.15000000000000002
    char text[32];
    std::snprintf(text, sizeof text, "%.15g", log ? a * std::pow(b / a, i / (n - 1)) : a + (b - a) * i / (n - 1));
    values.push_back(std::strtod(text, nullptr));
  }
  return values;
}

std::string HelpText(const std::string& command) {
  if (command == "run")
    return "usage: mechflow run FILE [--variant NAME]... [--set NAME=VALUE]... [--t-end T] [--out DIR]\n"
           "                    [--rtol R] [--atol A] [--interval DT] [--results NAME] [--quiet | --verbose]\n"
           "                    [--animate] [--gltf] [--no-animate] [--no-plot] [--overwrite] [--unsafe-lua]\n"
           "\n"
           "Simulates the diagram FILE and writes its logged signals as CSV (and the plot\n"
           "named in <output plot=...>) into DIR. Prints solver counters and the range of\n"
           "every logged signal.\n"
           "\n"
           "Files are named after the diagram (<diagram name>, <output csv>). DIR keeps a\n"
           "record, .mechflow-outputs, of which diagram file wrote the files of each name;\n"
           "a run whose files another diagram file wrote there (a copy keeping its\n"
           "<diagram name>) is refused before it starts (exit 2): give another --out,\n"
           "rename the outputs, or pass --overwrite. The same file again just overwrites.\n"
           "\n"
           "  --variant NAME    apply a named set of identifier values from the diagram's\n"
           "                    <variants> (repeatable, in order; `mechflow check` lists them)\n"
           "  --set NAME=VALUE  override an identifier defined by a number (repeatable,\n"
           "                    applied in order, after the variants; dependent\n"
           "                    identifiers follow); VALUE may be an expression of\n"
           "                    identifiers (2*c0), evaluated after the numbers\n"
           "  --set-file FILE   NAME=VALUE lines (# comments), as --set (a regular file)\n"
           "  --t-end T         end time [s], overrides <solver t_end>\n"
           "  --rtol R, --atol A  the solver's tolerances, override <solver>\n"
           "  --interval DT     the output grid [s], overrides <output interval>\n"
           "  --results NAME    the results file's name (default: <output csv> or NAME.csv)\n"
           "  --results -       the results CSV on standard output and nothing else there: every\n"
           "                    message (and a script's print) goes to standard error. No plot;\n"
           "                    the other files (NAME.units.csv, report, animation) go into\n"
           "                    --out DIR if given, else are not written (a note says which).\n"
           "                    A failed run leaves its rows up to the failure there (exit 1)\n"
           "  --no-plot         draw no plot (nor its .gp script, nor the <spectrum>s'): gnuplot\n"
           "                    is not needed; the CSV files and the animation are written alike\n"
           "  --overwrite       replace files another diagram file wrote in DIR (see above)\n"
           "  --quiet           print nothing but errors\n"
           "  --animate         write the animation NAME.html (the <shape>s of the bodies in 3D;\n"
           "                    <output animation=\"...\"> names it in the diagram)\n"
           "  --gltf            write the same scene and motion as glTF binary NAME.glb (Blender\n"
           "                    and other viewers; <output gltf=\"...\"> names it)\n"
           "  --no-animate      write neither, whatever the diagram's <output> asks (batch runs)\n"
           "  --verbose         also print the event log: every event's time, block, and for\n"
           "                    a mechanism the element and what it switched to\n"
           "  --out DIR         output folder (created if missing; default: current folder)\n"
           "  --unsafe-lua      give Lua code the io, os and package libraries\n"
           "  --allow-read DIR  the diagram may read files (tables, Lua, mechanisms) in DIR's\n"
           "                    folder tree too, not only in its own folder's (repeatable)\n"
           "  --library DIR     subsystem and part files not found beside the file naming\n"
           "                    them are looked up in DIR (repeatable, searched in order)\n"
           "  --max-output SIZE the budget per output file, bytes or with K, M, G, T (default 1G)\n"
           "Every option takes its value as --opt VALUE or --opt=VALUE; a number is the\n"
           "whole value in decimal (1e-3, -2.5, .5; not 0x10, inf or 1abc).\n"
           "\n"
           "Exit codes: 0 finished, 1 simulation failed (results up to the failure are\n"
           "written), 2 bad input, 130 / 143 / 129 ended by SIGINT (Ctrl-C) / SIGTERM /\n"
           "SIGHUP (the rows up to there are written).\n";
  if (command == "check")
    return "usage: mechflow check FILE [--variant NAME]... [--set NAME=VALUE]... [--allow-read DIR]...\n"
           "                      [--library DIR]...\n"
           "\n"
           "Reads and builds the diagram without running it, then prints the identifiers,\n"
           "the variants, the evaluation order of output ports, the continuous-state layout, the\n"
           "zero-crossing functions and the sampled blocks, then the subsystem and part\n"
           "instances as a tree (path, kind, file, the line including it). Exit 0 when the\n"
           "diagram is valid, 2 otherwise.\n";
  if (command == "graph")
    return "usage: mechflow graph FILE [--set NAME=VALUE]... [--allow-read DIR]...\n"
           "                      [--library DIR]...\n"
           "\n"
           "Prints the diagram as a Graphviz DOT graph on standard output, e.g.\n"
           "  mechflow graph d.xml | dot -Tsvg > d.svg\n"
           "Edges drawn bold carry direct feedthrough (they order the evaluation). The\n"
           "blocks of each subsystem instance are drawn in a box labelled with its path.\n";
  if (command == "modes")
    return "usage: mechflow modes FILE [--variant NAME]... [--set NAME=VALUE]... [--equilibrium]\n"
           "                      [--out DIR] [--overwrite] [--unsafe-lua]\n"
           "\n"
           "Linearises the diagram at its initial state (or, with --equilibrium, at the\n"
           "static equilibrium found first by damped Newton on x' = 0, the modes of\n"
           "contacts and friction chosen again at each rest state found until they agree\n"
           "with it) and prints its\n"
           "natural frequencies: damped f = |Im lambda| / 2 pi and undamped |lambda| / 2 pi\n"
           "[Hz], damping ratios -Re lambda / |lambda|, eigenvalues lambda [rad/s] and the\n"
           "mode shapes per state (coordinates and rates marked). Real eigenvalues\n"
           "(overdamped and rigid-body motions) are listed with frequency 0 and their\n"
           "decay rate. Elements that switch (friction stuck or sliding, regularised\n"
           "friction near rest, gear backlash, contacts) are listed with the mode they\n"
           "were linearised in: the frequencies hold only while those modes last, and\n"
           "an element stuck exactly locks a coordinate (a zero eigenvalue, no motion).\n"
           "Writes the same as NAME.modes.csv into DIR.\n"
           "\n"
           "  --variant NAME    apply a named set of identifier values (repeatable)\n"
           "  --set NAME=VALUE  override an identifier (repeatable, after the variants)\n"
           "  --equilibrium     linearise at the static equilibrium instead of the initial state\n"
           "  --out DIR         output folder for NAME.modes.csv (created if missing; default:\n"
           "                    current folder)\n"
           "  --overwrite       replace a NAME.modes.csv another diagram file wrote, as for run\n"
           "  --unsafe-lua      give Lua code the io, os and package libraries\n"
           "  --allow-read DIR, --library DIR  as for mechflow run\n"
           "\n"
           "Exit codes: 0 done, 1 no equilibrium found (modes that do not settle, or rates\n"
           "that are not finite), 2 bad input.\n";
  if (command == "force-analysis") return ForceAnalysisHelp();
  if (!command.empty() && IsTypeTopic(command)) return TypeHelp(command);
  if (command == "psd") return PsdHelp();
  if (command == "fit") return FitHelp();
  if (command == "export-fmu") return ExportFmuHelp();
  if (command == "sweep")
    return "usage: mechflow sweep FILE --vary NAME=V1,V2,... [--vary ...] [--variant NAME]...\n"
           "                      [--set NAME=VALUE]... [--t-end T] [--jobs N] [--out DIR] [--quiet | --verbose]\n"
           "                      [--no-plot] [--overwrite] [--unsafe-lua]\n"
           "\n"
           "Runs the diagram FILE once for every combination of the varied identifiers'\n"
           "values (the cartesian product; the last --vary changes fastest), N runs at a\n"
           "time, each with its own model and Lua state. Writes each run's results as\n"
           "NAME.runK.ID=VALUE....csv and one summary NAME.sweep.csv with a row per run in\n"
           "that order: run, the varied values, status (ok, stopped by the control\n"
           "script, or failed), t reached, error (or the reason for stopping),\n"
           "results file, then each <report> figure's value and time. A run that fails\n"
           "(solver failure, a value the model refuses) is a row with its error; the\n"
           "sweep goes on. NAME.sweep.png draws every run over one another, a panel per\n"
           "logged group, each curve labelled by its values. Ctrl-C, SIGTERM or SIGHUP\n"
           "ends the runs under way (their rows written), starts no more, writes the\n"
           "summary (`not run` rows) and exits 130, 143 or 129.\n"
           "\n"
           "  --vary NAME=V1,V2,...  values of an identifier defined by a number (repeatable);\n"
           "                    NAME=A:B:N gives N values evenly from A to B, NAME=A:B:N:log\n"
           "                    evenly on a log scale; [*] in NAME stands for every index, so\n"
           "                    s[*].mu=... gives s[0].mu, s[1].mu, ... each run's value alike\n"
           "  --jobs N          runs at a time (default: the number of cores)\n"
           "  --variant, --set, --t-end, --rtol, --atol, --interval, --results, --quiet,\n"
           "  --unsafe-lua, --allow-read, --library  as for mechflow run, for every run\n"
           "  --verbose         write each run's event log beside its results\n"
           "                    (NAME.runK.ID=VALUE....events.txt)\n"
           "  --max-output SIZE the budget per output file (each run's results), as for run\n"
           "  --out DIR         output folder (created if missing; default: current folder)\n"
           "  --no-plot         no overlay NAME.sweep.png (nor the envelopes it draws from)\n"
           "  --overwrite       replace files another diagram file wrote in DIR, as for run\n"
           "--results - is for mechflow run: a sweep writes a results file per run.\n"
           "\n"
           "Built with MPI (cmake -DMECHFLOW_MPI=ON), `mpirun -n K mechflow sweep ...`\n"
           "deals the runs to the K processes in turn (run i to process i mod K, each\n"
           "with N threads, default the cores divided by the processes on the machine);\n"
           "process 0 writes the summary, each process its runs' results.\n"
           "\n"
           "Exit codes: 0 every run finished, 1 some failed (the summary is written),\n"
           "2 bad input (an unknown or derived identifier, a value that is not a number).\n";
  return "usage: mechflow COMMAND FILE [options]\n"
         "\n"
         "mechflow simulates mechanisms with friction and contact described, with signal\n"
         "blocks, in an XML diagram (see diagrams/FORMAT.md).\n"
         "\n"
         "Commands:\n"
         "  run     simulate a diagram and write CSV and plot\n"
         "  check   validate a diagram and print its schedule and state layout\n"
         "  graph   print the diagram as Graphviz DOT\n"
         "  modes   natural frequencies, damping ratios and mode shapes\n"
         "  sweep   run every combination of identifier values, in parallel\n"
         "  force-analysis  dynamic stiffness, phase and loops of one force element\n"
         "  psd     power spectral density of logged signals in a results file\n"
         "  fit     fit friction and contact parameters to measured data\n"
         "  export-fmu  the diagram as an FMI 2.0 co-simulation FMU for another tool\n"
         "  help    help on a command, block type or diagram element: mechflow help run,\n"
         "          mechflow help integrator, mechflow help force\n"
         "\n"
         "Options: --help (also after a command), --version.\n" +
         TopicsText();
}

void ReadSetFile(const std::string& text, const std::string& path, Arguments* a) {
  std::istringstream in(text);
  int number = 0;
  for (std::string line; std::getline(in, line);) {
    if (++number == 1) line = std::string(blocks::WithoutByteOrderMark(line));  // as spreadsheets save it
    line = line.substr(0, line.find('#'));
    const auto first = line.find_first_not_of(" \t\r"), last = line.find_last_not_of(" \t\r");
    if (first == std::string::npos) continue;
    AddSet(line.substr(first, last - first + 1), path + ":" + std::to_string(number), a);
  }
}

Arguments ParseArguments(const std::vector<std::string>& args) {
  Arguments a;
  size_t i = 0;
  if (args.empty()) throw UsageError("no command given");
  const std::string& first = args[0];
  if (first == "--help" || first == "-h") {
    a.help = true;
    return a;
  }
  if (first == "--version") {
    a.version = true;
    return a;
  }
  if (first == "help") {
    a.help = true;
    if (args.size() > 1) a.command = args[1];
    if (!a.command.empty() && std::find(kCommands.begin(), kCommands.end(), a.command) == kCommands.end() &&
        !IsTypeTopic(a.command)) {
      std::vector<std::string> topics = kCommands;
      for (const std::string& t : TypeTopics()) topics.push_back(t);
      throw UsageError("no help topic '" + blocks::Excerpt(a.command) + "'" + blocks::DidYouMean(a.command, topics) +
                       "; `mechflow help` lists the commands, block types and diagram elements");
    }
    return a;
  }
  if (std::find(kCommands.begin(), kCommands.end(), first) == kCommands.end())
    throw UsageError("unknown command '" + first + "'" + blocks::DidYouMean(first, kCommands) +
                     "; commands: " + blocks::JoinNames(kCommands));
  a.command = first;
  for (i = 1; i < args.size(); ++i) {
    // --opt=value as well as --opt value
    std::string arg = args[i];
    std::optional<std::string> inline_value;
    if (arg.rfind("--", 0) == 0 && arg.find('=') != std::string::npos) {
      inline_value = arg.substr(arg.find('=') + 1);
      arg = arg.substr(0, arg.find('='));
    }
    auto value = [&](const std::string& option) -> std::string {
      if (inline_value) return *inline_value;
      if (i + 1 >= args.size()) throw UsageError(option + " needs a value");
      return args[++i];
    };
    const bool runs = a.command == "run" || a.command == "sweep";
    const bool fit = a.command == "fit";
    if (arg == "--help" || arg == "-h") {
      a.help = true;
    } else if (fit && std::find(kFitOptions.begin(), kFitOptions.end(), arg) != kFitOptions.end()) {
      // in order: a --variant or --set after a --data is that experiment's
      a.command_options.emplace_back(arg, value(arg));
    } else if (arg == "--set") {
      AddSet(value(arg), "--set", &a);
    } else if (arg == "--set-file") {
      // NAME=VALUE lines (OpenModelica's override file); '#' starts a comment
      const std::string path = value(arg);
      std::string text;
      try {  // a regular file of bounded size: not a FIFO that blocks, nor /dev/zero
        text = blocks::ReadInputFile(path, "file");
      } catch (const InputError& e) {
        throw UsageError(std::string("--set-file: ") + e.what());
      }
      ReadSetFile(text, path, &a);
    } else if (arg == "--variant") {
      a.variants.push_back(value(arg));
    } else if (arg == "--t-end") {
      a.t_end = ParseNumber(value(arg), arg);
    } else if (arg == "--out") {
      a.out_dir = value(arg);
      a.out_given = true;
    } else if (arg == "--rtol" && runs) {
      a.rtol = ParseNumber(value(arg), arg);
    } else if (arg == "--atol" && runs) {
      a.atol = ParseNumber(value(arg), arg);
    } else if (arg == "--interval" && runs) {
      a.interval = ParseNumber(value(arg), arg);
    } else if (arg == "--max-output" && runs) {
      a.max_output_bytes = ParseByteSize(value(arg), arg);
    } else if (arg == "--results" && runs) {
      a.results = value(arg);
    } else if (arg == "--animate" && a.command == "run") {
      a.animate = true;
    } else if (arg == "--gltf" && a.command == "run") {
      a.gltf = true;
    } else if (arg == "--no-animate" && a.command == "run") {
      a.no_animate = true;
    } else if (arg == "--no-plot" && (runs || fit)) {
      a.no_plot = true;
    } else if (arg == "--overwrite" && (runs || fit || a.command == "modes")) {
      a.overwrite = true;
    } else if (arg == "--quiet" && runs) {
      a.quiet = true;
    } else if (arg == "--verbose" && runs) {
      a.verbose = true;
    } else if (arg == "--equilibrium" && a.command == "modes") {
      a.equilibrium = true;
    } else if (arg == "--unsafe-lua") {
      a.unsafe_lua = true;
    } else if (arg == "--allow-read" && a.command != "psd") {
      a.allow_read.push_back(value(arg));
    } else if (arg == "--library" && a.command != "psd") {
      a.library.push_back(value(arg));
    } else if (const auto& own = CommandOptions(a.command); std::find(own.begin(), own.end(), arg) != own.end()) {
      a.command_options.emplace_back(arg, value(arg));
    } else if (arg == "--vary" && (a.command == "sweep" || a.command == "force-analysis")) {
      a.vary.push_back(ParseVary(value(arg)));
    } else if (arg == "--jobs" && (a.command == "sweep" || fit)) {
      a.jobs = ParseCount(value(arg), arg, 1, 4096);
    } else if (arg.rfind("--", 0) == 0) {
      std::vector<std::string> options = {"--set", "--set-file", "--variant", "--t-end", "--out", "--unsafe-lua", "--help"};
      if (runs) options.insert(options.end(), {"--rtol", "--atol", "--interval", "--results", "--quiet"});
      if (a.command != "psd") options.insert(options.end(), {"--allow-read", "--library"});
      if (runs) options.insert(options.end(), {"--max-output", "--no-plot", "--overwrite"});
      if (a.command == "modes") options.insert(options.end(), {"--equilibrium", "--overwrite"});
      if (a.command == "run") options.insert(options.end(), {"--animate", "--gltf", "--no-animate"});
      if (a.command == "sweep") options.insert(options.end(), {"--vary", "--jobs"});
      if (fit) options.insert(options.end(), {"--jobs", "--no-plot", "--overwrite"});
      if (a.command == "force-analysis") options.push_back("--vary");
      options.insert(options.end(), CommandOptions(a.command).begin(), CommandOptions(a.command).end());
      throw UsageError("unknown option '" + arg + "'" + blocks::DidYouMean(arg, options) + "; see mechflow help " +
                       a.command);
    } else if (a.file.empty()) {
      a.file = arg;
    } else {
      throw UsageError("unexpected argument '" + arg + "' (the diagram file is '" + a.file + "')");
    }
  }
  if (!a.help && a.file.empty()) throw UsageError("mechflow " + a.command + " needs a diagram FILE");
  if (a.quiet && a.verbose) throw UsageError("--quiet and --verbose contradict each other; give one");
  if (a.no_animate && (a.animate || a.gltf))
    throw UsageError(std::string("--no-animate and ") + (a.animate ? "--animate" : "--gltf") +
                     " contradict each other; give one");
  if (a.results == "-" && a.command == "sweep")
    throw UsageError("--results - (standard output) is for mechflow run: a sweep writes a results file per run; "
                     "give --results NAME.csv (each run's file is named from it) or leave it out");
  if (a.results == "-" && !a.out_given && (a.animate || a.gltf))
    throw UsageError(std::string(a.animate ? "--animate" : "--gltf") +
                     " writes a file into the output folder, and --results - without --out has none: give --out DIR "
                     "for it (the results still go to standard output)");
  if (!a.help && a.command == "sweep" && a.vary.empty())
    throw UsageError("mechflow sweep needs at least one --vary NAME=V1,V2,...");
  return a;
}

}  // namespace mechflow::cli
