#include "cli/plot.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <sstream>

#include "cli/gnuplot_text.h"

extern char** environ;

namespace mechflow::cli {
namespace {

// One column's curve: from the CSV, or from an envelope (the band between its
// min and max, and both lines) in the colour of the `curve`-th curve. A
// plain curve takes that colour only when `coloured` (else gnuplot's own
// order gives it).
std::string Curve(const std::string& file, int x, int y, bool envelope, int curve, const std::string& title,
                  bool coloured = false) {
  std::ostringstream s;
  if (!envelope) {
    s << file << " using " << x << ":" << y << " every ::1 with lines lw 1.5 "
      << (coloured ? "lc " + std::to_string(curve) + " " : "") << "title " << GnuplotQuote(title);
    return s.str();
  }
  s << file << " using " << x << ":" << y << ":" << y + 1 << " every ::1 with filledcurves fs solid noborder lc "
    << curve << " notitle, \\\n       '' using " << x << ":" << y << " every ::1 with lines lw 1.5 lc " << curve
    << " title " << GnuplotQuote(title) << ", \\\n       '' using " << x << ":" << y + 1
    << " every ::1 with lines lw 1.5 lc " << curve << " notitle";
  return s.str();
}

}  // namespace

std::string GnuplotScript(const blocks::Results& results, const std::vector<diagrams::PlotGroup>& groups,
                          const std::string& title, const std::string& csv_name, const std::string& plot_name,
                          const std::vector<diagrams::XYPlotRequest>& xy, const EnvelopeFiles& envelope) {
  const PlotEnvelope* e = envelope.envelope;
  const std::string note =
      e ? " (" + std::to_string(e->rows()) + " rows, drawn as their min and max per pixel column)" : "";
  std::ostringstream s;
  s << GnuplotPreamble(plot_name, static_cast<int>(groups.size() + xy.size()), 260, 22, title + note)
    << "set xlabel 'time [s]'\n";
  for (const auto& g : groups) {
    // the group's name on its axis too, with the unit of its columns
    s << "set title " << GnuplotQuote(g.name) << "\nset ylabel " << GnuplotQuote(g.axis_label) << "\n";
    s << "plot ";
    for (size_t i = 0; i < g.columns.size(); ++i) {
      const int c = g.columns[i];
      const std::string file = i ? "''" : GnuplotQuote(e ? envelope.name : csv_name);
      s << (i ? ", \\\n     " : "")
        << Curve(file, e ? 4 : 1, e ? e->MinColumn(c) : c + 1, e, static_cast<int>(i) + 1, results.columns()[c]);
    }
    s << "\n";
  }
  for (const diagrams::XYPlotRequest& p : xy) {
    // a long run's x-y curve goes through the rows holding each bin's extremes
    s << "set title " << GnuplotQuote(p.title + (e ? " (extreme rows of each pixel column of time)" : ""))
      << "\nset xlabel " << GnuplotQuote(p.x_label) << "\nset ylabel " << GnuplotQuote(p.y_label) << "\nplot ";
    for (std::size_t i = 0; i < p.curves.size(); ++i) {
      const auto [x, y] = p.curves[i];
      s << (i ? ", \\\n     " : "") << (i ? "''" : GnuplotQuote(e ? envelope.xy_name : csv_name)) << " using "
        << (e ? e->XYColumn(x) : x + 1) << ":" << (e ? e->XYColumn(y) : y + 1)
        << " every ::1 with lines lw 1.5 title " << GnuplotQuote(results.columns()[y] + " : " + results.columns()[x]);
    }
    s << "\n";
  }
  if (groups.empty() && xy.empty()) s << "set title 'nothing logged'\nunset key\nplot [0:1] 0 notitle\n";
  s << "unset multiplot\n";
  return s.str();
}

std::string OverlayScript(const std::vector<diagrams::PlotGroup>& groups, const std::vector<std::string>& columns,
                          const std::vector<OverlayRun>& runs, const std::string& title, const std::string& plot_name) {
  const std::vector<int> plotted = PlottedColumns(groups);
  std::ostringstream s;
  s << GnuplotPreamble(plot_name, static_cast<int>(groups.size()), 300, 28, title) << "set xlabel 'time [s]'\n";
  bool enveloped = false;  // a long run's curves are bands: every curve gets its colour by number
  for (const OverlayRun& run : runs) enveloped = enveloped || !run.envelope_name.empty();
  for (const auto& g : groups) {
    s << "set title " << GnuplotQuote(g.name) << "\nset ylabel " << GnuplotQuote(g.axis_label) << "\nplot ";
    int curve = 0;
    for (const OverlayRun& run : runs)
      for (const int c : g.columns) {
        const std::string label = g.columns.size() > 1 ? run.label + " " + columns[c] : run.label;
        const bool band = !run.envelope_name.empty();
        s << (curve ? ", \\\n     " : "");
        ++curve;
        if (band) s << Curve(GnuplotQuote(run.envelope_name), 4, EnvelopeMinColumn(plotted, c), true, curve, label);
        else s << Curve(GnuplotQuote(run.csv_name), 1, c + 1, false, curve, label, enveloped);
      }
    if (!curve) s << "[0:1] 0 notitle";
    s << "\n";
  }
  if (groups.empty()) s << "set title 'nothing logged'\nunset key\nplot [0:1] 0 notitle\n";
  s << "unset multiplot\n";
  return s.str();
}

std::string DrawPlot(const std::string& script, const OutputFolder& folder, const std::string& plot_name) {
  std::string script_name = plot_name + ".gp";
  folder.Write(script_name, script);
  folder.Clear(plot_name);  // so that a plot there afterwards is gnuplot's
  // no shell, and gnuplot runs in the output folder, so that the script
  // names only the plain file names of the diagram
  std::string program = "gnuplot";
  std::vector<char*> argv = {program.data(), script_name.data(), nullptr};
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addchdir_np(&actions, folder.path().c_str());
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  pid_t pid = 0;
  const int error = posix_spawnp(&pid, "gnuplot", &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (error == ENOENT) return "gnuplot not found (install it: apt-get install gnuplot-nox)";
  if (error != 0) return std::string("cannot start gnuplot: ") + std::strerror(error);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw WriteError("gnuplot failed on '" + folder.PathOf(script_name) + "' (its messages are above)");
  if (!folder.HasFile(plot_name))
    throw WriteError("gnuplot made no '" + folder.PathOf(plot_name) + "' (is the disk full?)");
  return "";
}

}  // namespace mechflow::cli
