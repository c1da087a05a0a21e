#include "cli/force_analysis_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "analysis/force_analysis.h"
#include "blocks/outputs/csv.h"
#include "blocks/support/message_number.h"
#include "cli/interrupt.h"
#include "cli/output_folder.h"
#include "cli/plot.h"
#include "cli/xy_plot.h"

namespace mechflow::cli {
namespace {

using blocks::MessageNumber;

constexpr double kDegrees = 57.29577951308232;

// Amplitudes and frequencies: every value > 0 (`what` says which).
std::vector<double> PositiveValues(const std::string& text, const std::string& option, const std::string& what) {
  std::vector<double> values = ParseValues(text, option);
  for (double v : values)
    if (!(v > 0))
      throw UsageError(option + ": '" + text + "' holds " + MessageNumber(v) + "; " + what + " must be > 0");
  return values;
}

std::string CaseLabel(const analysis::ForceAnalysisRequest& request, const analysis::ForceAnalysisCase& c) {
  std::string label;
  for (std::size_t i = 0; i < c.varied.size(); ++i)
    label += request.vary[i].first.front() + "=" + MessageNumber(c.varied[i]) + " ";
  return label + "a=" + MessageNumber(c.amplitude) + " f=" + MessageNumber(c.frequency);
}

}  // namespace

const std::vector<std::string> kForceAnalysisOptions = {"--element", "--component", "--amplitude", "--frequency",
                                                        "--frequencies", "--cycles", "--samples"};

std::string ForceAnalysisHelp() {
  return "usage: mechflow force-analysis FILE --element NAME --amplitude A[,A...]\n"
         "                              (--frequency F[,F...] | --frequencies F1:F2:N)\n"
         "                              [--component C] [--vary NAME[,NAME...]=V1,V2,...]...\n"
         "                              [--cycles N] [--samples N] [--variant NAME]... [--set NAME=VALUE]...\n"
         "                              [--out DIR] [--unsafe-lua]\n"
         "\n"
         "Drives one force element of the diagram alone along its own coordinate (a\n"
         "line's length, a joint coordinate, a contact's penetration, a bushing\n"
         "component) as x = x0 + a sin(2 pi f t), x0 its value in the initial\n"
         "configuration, every other body held there at rest, and prints per case the\n"
         "dynamic stiffness K = |R1|/a and phase delta = arg R1 - arg x1 of the first\n"
         "harmonic of the reaction R = -F (the force that imposes the motion), its\n"
         "amplitude |R1| and the loop energy (the work done on the element per cycle).\n"
         "Writes NAME.force_analysis.csv (those figures), NAME.force_analysis.loops.csv\n"
         "(x', v, R over the last cycle of every case) and the plots\n"
         "NAME.force_analysis.loops.png (R against x' and against v) and\n"
         "NAME.force_analysis.png (K and delta against frequency, or against the first\n"
         "varied identifier).\n"
         "\n"
         "  --element NAME      the force element (a <force>, <joint_force>, <contact> or <bushing>)\n"
         "  --component C       a bushing's dx, dy, dz (m) or ax, ay, az (rad)\n"
         "  --amplitude A,...   amplitudes [m or rad], > 0 (or a range A:B:N, A:B:N:log)\n"
         "  --frequency F,...   frequencies [Hz], > 0 (or a range, as --amplitude)\n"
         "  --frequencies F1:F2:N  N frequencies from F1 to F2, evenly spaced on a log scale\n"
         "  --vary NAME=V1,...  repeat for every value of the identifier (repeatable; the\n"
         "                      cartesian product); NAME1,NAME2=... sets several alike\n"
         "                      (e.g. a static and a dynamic friction coefficient)\n"
         "  --cycles N          periods run per case (default 10, 2 to 100000); the last is\n"
         "                      analysed and must repeat the one before to 1e-6 of its\n"
         "                      largest force (else the case is marked not periodic)\n"
         "  --samples N         rows per period (default 1000, 16 to 1000000; at most 10^7\n"
         "                      rows per case in all)\n"
         "  --variant, --set, --unsafe-lua, --allow-read, --library   as for mechflow run\n"
         "  --out DIR           output folder (created if missing; default: current folder)\n"
         "\n"
         "Example: mechflow force-analysis diagrams/examples/elast_friction2.xml --element friction\n"
         "           --amplitude 0.001,0.002,0.003 --frequency 1 --vary ffr,ffr0=0,0.1,0.2,0.3,0.5\n"
         "\n"
         "Exit codes: 0 every case periodic, 1 a case failed (its numbers overflowed, say)\n"
         "or did not become periodic (all results written), 2 bad input, 130 / 143 ended\n"
         "by SIGINT / SIGTERM (the cases finished by then written, no plots).\n";
}

int ForceAnalysisCommand(const Arguments& args, std::ostream& out, std::ostream& err) {
  analysis::ForceAnalysisRequest request;
  request.file = args.file;
  request.options.variants = args.variants;
  request.options.overrides = args.overrides;
  request.options.expression_overrides = args.set_expressions;
  request.options.unsafe_lua = args.unsafe_lua;
  request.options.allow_read = args.allow_read;
  request.options.library = args.library;
  for (const auto& [option, value] : args.command_options) {
    if (option == "--element") request.element = value;
    else if (option == "--component") request.component = value;
    else if (option == "--amplitude") request.amplitudes = PositiveValues(value, option, "an amplitude");
    else if (option == "--frequency") request.frequencies = PositiveValues(value, option, "a frequency");
    else if (option == "--frequencies") {
      if (std::count(value.begin(), value.end(), ':') != 2)
        throw UsageError("--frequencies expects F1:F2:N, got '" + value + "'");
      request.frequencies = PositiveValues(value + ":log", option, "a frequency");
    }
    else if (option == "--cycles") request.cycles = ParseCount(value, option, 2, 100000);
    else if (option == "--samples") request.samples = ParseCount(value, option, 16, 1000000);
  }
  if (request.element.empty()) throw UsageError("needs --element NAME (the force element to drive)");
  if (args.t_end) throw UsageError("--t-end does not apply: each case runs --cycles periods of its frequency");
  for (const auto& [names, values] : args.vary) {
    std::vector<std::string> split;
    std::stringstream in(names);
    for (std::string name; std::getline(in, name, ',');) split.push_back(name);
    request.vary.emplace_back(split, values);
  }
  const OutputFolder folder(args.out_dir);
  const InterruptHandlers handlers;  // Ctrl-C, SIGTERM: the case under way ends, the finished ones are written
  request.interrupt = InterruptFlag();
  const analysis::ForceAnalysis fa = analysis::RunForceAnalysis(request);
  const std::string base = fa.diagram + ".force_analysis";
  if (fa.interrupted)
    err << "mechflow force-analysis: " << analysis::SignalName(fa.interrupted) << " after " << fa.cases.size()
        << " of " << fa.planned << " cases; writing those, no plots\n";

  // the table: stdout and CSV
  std::ostringstream csv;
  out << "mechflow force-analysis " << args.file << ": " << fa.element_what << ", x = x0 + a sin(2 pi f t), "
      << "reaction R = -F; " << fa.cases.size() << " case" << (fa.cases.size() == 1 ? "" : "s") << "\n";
  std::string header;
  for (const auto& v : request.vary) {  // "ffr=ffr0": both take the row's value
    std::string names;
    for (const std::string& n : v.first) names += (names.empty() ? "" : "=") + n;
    header += blocks::CsvField(names) + ",";
  }
  header += "amplitude,frequency [Hz],x0,K,delta [deg],force amplitude,loop energy,periodic,error";
  csv << header << "\n";
  char line[256];
  for (const auto& v : request.vary) {
    std::snprintf(line, sizeof line, "%10s ", v.first.front().c_str());
    out << line;
  }
  out << "  amplitude    f [Hz]            K   delta [deg]          |R1|   loop energy   periodic\n";
  int bad = 0;
  for (const analysis::ForceAnalysisCase& c : fa.cases) {
    for (double v : c.varied) {
      std::snprintf(line, sizeof line, "%10.4g ", v);
      out << line;
      csv << blocks::CsvNumber(v) << ",";
    }
    std::snprintf(line, sizeof line, "%11.4g %9.4g %12.6g %13.6g %13.6g %13.6g   %s\n", c.amplitude, c.frequency,
                  c.stiffness, c.phase * kDegrees, c.force_amplitude, c.loop_energy,
                  !c.failure.empty() ? "failed" : c.periodic ? "yes" : "NO");
    out << line;
    if (!c.failure.empty()) err << "  failed: " << c.failure << "\n";
    else if (!c.periodic) err << "  not periodic after " << request.cycles << " cycles: the last two differ by "
                              << c.periodic_error << " of the largest force (raise --cycles)\n";
    bad += !c.failure.empty() || !c.periodic;
    csv << blocks::CsvNumber(c.amplitude) << "," << blocks::CsvNumber(c.frequency) << "," << blocks::CsvNumber(c.x0)
        << "," << blocks::CsvNumber(c.stiffness) << "," << blocks::CsvNumber(c.phase * kDegrees) << ","
        << blocks::CsvNumber(c.force_amplitude) << "," << blocks::CsvNumber(c.loop_energy)
        << "," << (c.periodic ? "yes" : "no") << "," << blocks::CsvField(c.failure) << "\n";
  }
  folder.Write(base + ".csv", csv.str());
  out << "wrote " << folder.PathOf(base + ".csv") << "\n";

  // the loops of the last period, three columns per case
  std::ostringstream loops;
  std::vector<XYCurve> against_x, against_v;
  for (std::size_t i = 0; i < fa.cases.size(); ++i) {
    const std::string label = CaseLabel(request, fa.cases[i]);
    loops << (i ? "," : "") << "x' " << label << ",v " << label << ",R " << label;
    const int first = static_cast<int>(3 * i);
    against_x.push_back({first, first + 2, label});
    against_v.push_back({first + 1, first + 2, label});
  }
  loops << "\n";
  const std::size_t rows = fa.cases.empty() ? 0 : fa.cases.front().x.size();
  for (std::size_t k = 0; k < rows; ++k) {
    for (std::size_t i = 0; i < fa.cases.size(); ++i) {
      const auto& c = fa.cases[i];
      const bool has = k < c.x.size();
      loops << (i ? "," : "") << (has ? blocks::CsvNumber(c.x[k]) : "") << ","
            << (has ? blocks::CsvNumber(c.v[k]) : "") << "," << (has ? blocks::CsvNumber(c.reaction[k]) : "");
    }
    loops << "\n";
  }
  folder.Write(base + ".loops.csv", loops.str());
  out << "wrote " << folder.PathOf(base + ".loops.csv") << "\n";
  if (fa.interrupted) return 128 + fa.interrupted;  // 130 SIGINT, 143 SIGTERM
  const std::string loops_plot = base + ".loops.png";
  std::string warning = DrawPlot(XYPlotScript({{"reaction against displacement (hysteresis)", "x' = x - x0", "R = -F",
                                                against_x},
                                               {"reaction against velocity", "v", "R = -F", against_v}},
                                              fa.diagram + ": " + fa.element_what, base + ".loops.csv", loops_plot),
                                 folder, loops_plot);
  if (warning.empty()) out << "wrote " << folder.PathOf(loops_plot) << "\n";

  // K and delta against frequency, or against the first varied identifier:
  // one column of x values, then per curve a K and a delta column
  const bool by_frequency = request.frequencies.size() > 1;
  const bool by_value = !by_frequency && !request.vary.empty() && request.vary.front().second.size() > 1;
  if (warning.empty() && (by_frequency || by_value)) {
    const std::vector<double>& xs = by_frequency ? request.frequencies : request.vary.front().second;
    const int n = static_cast<int>(xs.size()), curves = static_cast<int>(fa.cases.size()) / n;
    // cases run varied (first slowest), amplitude, frequency (fastest)
    auto case_of = [&](int curve, int point) -> const analysis::ForceAnalysisCase& {
      return by_frequency ? fa.cases[curve * n + point] : fa.cases[point * curves + curve];
    };
    std::ostringstream table;
    std::vector<XYCurve> k_curves, delta_curves;
    table << (by_frequency ? "frequency [Hz]" : request.vary.front().first.front());
    for (int j = 0; j < curves; ++j) {
      const analysis::ForceAnalysisCase& c = case_of(j, 0);
      std::string label = "a=" + MessageNumber(c.amplitude);
      if (!by_frequency) label += " f=" + MessageNumber(c.frequency);
      for (std::size_t i = by_frequency ? 0 : 1; i < c.varied.size(); ++i)
        label += " " + request.vary[i].first.front() + "=" + MessageNumber(c.varied[i]);
      table << ",K " << label << ",delta " << label;
      k_curves.push_back({0, 1 + 2 * j, label, true});
      delta_curves.push_back({0, 2 + 2 * j, label, true});
    }
    table << "\n";
    for (int i = 0; i < n; ++i) {
      table << blocks::CsvNumber(xs[i]);
      for (int j = 0; j < curves; ++j)
        table << "," << blocks::CsvNumber(case_of(j, i).stiffness) << ","
              << blocks::CsvNumber(case_of(j, i).phase * kDegrees);
      table << "\n";
    }
    const std::string x_label = by_frequency ? "frequency [Hz]" : request.vary.front().first.front();
    folder.Write(base + ".curves.csv", table.str());
    const std::string plot = base + ".png";
    warning = DrawPlot(XYPlotScript({{"dynamic stiffness K = |R1| / a", x_label, "K", k_curves, by_frequency, false,
                                      0.0, true},
                                     {"phase delta = arg R1 - arg x1", x_label, "delta [deg]", delta_curves,
                                      by_frequency, false, 0.0, true}},
                                    fa.diagram + ": " + fa.element_what, base + ".curves.csv", plot),
                       folder, plot);
    if (warning.empty()) out << "wrote " << folder.PathOf(plot) << " (data " << base << ".curves.csv)\n";
  }
  if (!warning.empty()) err << "warning: no plot: " << warning << "\n";
  return bad ? 1 : 0;
}

}  // namespace mechflow::cli
