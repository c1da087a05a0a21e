#pragma once
// Command-line parsing for `mechflow COMMAND FILE [options]`.

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace mechflow::cli {

struct Arguments {
  std::string command;  // run, check, graph, modes, sweep, help
  std::string file;
  std::vector<std::string> variants;                      // --variant NAME
  std::vector<std::pair<std::string, double>> overrides;  // --set NAME=VALUE
  std::vector<std::pair<std::string, std::string>> set_expressions;  // --set NAME=EXPR (not a number)
  std::optional<double> t_end;                            // --t-end T
  std::optional<double> rtol, atol, interval;             // --rtol, --atol, --interval
  std::optional<std::string> results;                     // --results NAME ("-": standard output, run only)
  bool quiet = false;                                     // --quiet: errors only
  bool verbose = false;                                   // run --verbose: the event log
  bool animate = false;                                   // run --animate: write NAME.html
  bool gltf = false;                                      // run --gltf: write NAME.glb
  bool no_animate = false;                                // run --no-animate: neither, whatever <output> says
  std::string out_dir = ".";                              // --out DIR
  bool out_given = false;                                 // --out was given (run --results - writes no file without)
  bool no_plot = false;                                   // run, sweep --no-plot: gnuplot draws nothing
  bool overwrite = false;                                 // run, sweep, modes --overwrite: take over another
                                                          // diagram's file names in --out (cli/output_claims.h)
  bool unsafe_lua = false;                                // --unsafe-lua
  std::vector<std::string> allow_read;                    // --allow-read DIR: the diagram may read files there too
  std::vector<std::string> library;                       // --library DIR: subsystem and part files looked up there
  bool equilibrium = false;                               // modes --equilibrium
  std::vector<std::pair<std::string, std::vector<double>>> vary;  // sweep --vary NAME=V1,V2,...
  std::optional<int> jobs;                                // sweep --jobs N (>= 1)
  std::optional<std::uint64_t> max_output_bytes;          // run, sweep --max-output SIZE: bytes per output file
  // options of one command only (force-analysis ...), with their values, in
  // order; that command reads them
  std::vector<std::pair<std::string, std::string>> command_options;
  bool help = false;                                      // help for `command` (or general)
  bool version = false;
};

// The NAME=VALUE lines of a --set-file's `text` ('#' starts a comment),
// added to `a` as --set options are; UsageError naming path:line.
void ReadSetFile(const std::string& text, const std::string& path, Arguments* a);

// Throws UsageError with a message for bad command lines.
Arguments ParseArguments(const std::vector<std::string>& args);

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A finite number, the whole text in decimal (1e-3, -2.5, .5; not 0x10, inf,
// nan, 1abc or ""), or UsageError naming `option` and the text.
double ParseNumber(const std::string& text, const std::string& option);
// A whole number from `min` to `max`, digits only (not 1e3, 2.0 or 0x10), or
// UsageError naming `option`, the text and the range.
int ParseCount(const std::string& text, const std::string& option, int min, int max);
// Values as a list "V1,V2,..." or a range "A:B:N" (evenly spaced) or
// "A:B:N:log" (evenly on a log scale); UsageError naming `option`.
std::vector<double> ParseValues(const std::string& spec, const std::string& option);

// Help texts: general (command empty) or per command.
std::string HelpText(const std::string& command);

}  // namespace mechflow::cli
