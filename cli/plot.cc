#include "cli/plot.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>

#include "cli/gnuplot_text.h"
#include "cli/interrupt.h"

extern char** environ;

namespace mechflow::cli {
namespace {

// One column's curve: from the CSV, or from an envelope (the band between its
// min and max, and both lines), in the look of the `curve`-th curve of its
// panel (CurveStyle, from 0).
std::string Curve(const std::string& file, int x, int y, bool envelope, int curve, const std::string& title) {
  const std::string style = CurveStyle(curve);
  std::ostringstream s;
  if (!envelope) {
    s << file << " using " << x << ":" << y << " every ::1 with lines lw 1.5 " << style << " title "
      << GnuplotQuote(title);
    return s.str();
  }
  s << file << " using " << x << ":" << y << ":" << y + 1 << " every ::1 with filledcurves fs solid noborder "
    << style << " notitle, \\\n       '' using " << x << ":" << y << " every ::1 with lines lw 1.5 " << style
    << " title " << GnuplotQuote(title) << ", \\\n       '' using " << x << ":" << y + 1
    << " every ::1 with lines lw 1.5 " << style << " notitle";
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
        << Curve(file, e ? 4 : 1, e ? e->MinColumn(c) : c + 1, e, static_cast<int>(i), results.columns()[c]);
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
        << " every ::1 with lines lw 1.5 " << CurveStyle(static_cast<int>(i)) << " title "
        << GnuplotQuote(results.columns()[y] + " : " + results.columns()[x]);
    }
    s << "\n";
  }
  if (groups.empty() && xy.empty()) s << "set title 'nothing logged'\nunset key\nplot [0:1] 0 notitle\n";
  s << "unset multiplot\n";
  return s.str();
}

std::vector<std::string> LegendNumbers(const std::vector<double>& values) {
  for (int digits = 6;; ++digits) {
    std::vector<std::string> texts;
    std::map<std::string, double> seen;  // a text and the value it showed
    bool distinct = true;
    for (const double v : values) {
      char buffer[64];
      const auto end =
          std::to_chars(buffer, buffer + sizeof buffer, v == 0.0 ? 0.0 : v, std::chars_format::general, digits).ptr;
      texts.emplace_back(buffer, end);
      const auto [at, added] = seen.emplace(texts.back(), v);
      distinct = distinct && (added || at->second == v);
    }
    if (distinct || digits >= 17) return texts;  // 17 digits tell every two doubles apart
  }
}

std::string OverlayScript(const std::vector<diagrams::PlotGroup>& groups, const std::vector<std::string>& columns,
                          const std::vector<OverlayRun>& runs, const std::string& title, const std::string& plot_name) {
  const std::vector<int> plotted = PlottedColumns(groups);
  std::ostringstream s;
  s << GnuplotPreamble(plot_name, static_cast<int>(groups.size()), 300, 28, title) << "set xlabel 'time [s]'\n";
  for (const auto& g : groups) {
    s << "set title " << GnuplotQuote(g.name) << "\nset ylabel " << GnuplotQuote(g.axis_label) << "\nplot ";
    int curve = 0;
    for (const OverlayRun& run : runs)
      for (const int c : g.columns) {
        const std::string label = g.columns.size() > 1 ? run.label + " " + columns[c] : run.label;
        const bool band = !run.envelope_name.empty();
        s << (curve ? ", \\\n     " : "");
        if (band) s << Curve(GnuplotQuote(run.envelope_name), 4, EnvelopeMinColumn(plotted, c), true, curve, label);
        else s << Curve(GnuplotQuote(run.csv_name), 1, c + 1, false, curve, label);
        ++curve;
      }
    if (!curve) s << "[0:1] 0 notitle";
    s << "\n";
  }
  if (groups.empty()) s << "set title 'nothing logged'\nunset key\nplot [0:1] 0 notitle\n";
  s << "unset multiplot\n";
  return s.str();
}

namespace {

// Once a signal has stopped one plot, the command starts no more.
int g_plots_stopped_by = 0;

// "" when gnuplot's plot file has its end: a PNG's IEND chunk, an SVG's
// closing tag; else what is missing. A full disk cuts the file while gnuplot
// still exits 0.
std::string MissingEnd(const std::string& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  const std::streamoff size = in ? static_cast<std::streamoff>(in.tellg()) : 0;
  std::string tail(static_cast<std::size_t>(std::min<std::streamoff>(size, 64)), '\0');
  in.seekg(size - static_cast<std::streamoff>(tail.size()));
  if (!in.read(tail.data(), static_cast<std::streamsize>(tail.size()))) return "it cannot be read back";
  if (std::filesystem::path(path).extension() == ".svg") {
    while (!tail.empty() && std::isspace(static_cast<unsigned char>(tail.back()))) tail.pop_back();
    return tail.ends_with("</svg>") ? "" : "it has no closing </svg>";
  }
  static const std::string kIend("\0\0\0\0IEND\xae\x42\x60\x82", 12);  // an empty IEND chunk and its CRC
  return tail.ends_with(kIend) ? "" : "it has no PNG end (IEND chunk)";
}

// Starts gnuplot on `script_name` in `folder`: no shell, standard input
// /dev/null (so nothing typed or piped to mechflow reaches it), standard
// output /dev/null, the script named "./NAME" (never taken for an option).
// It stays in mechflow's process group, so Ctrl-Z and the terminal's job
// control treat the two as one, but with SIGINT and SIGHUP blocked: the
// terminal's Ctrl-C or hangup reaches mechflow, which stops gnuplot with
// SIGTERM (left at its default action) once. Returns 0 or posix_spawn's error.
int StartGnuplot(const OutputFolder& folder, const std::string& script_name, pid_t* pid) {
  std::string program = "gnuplot", script = "./" + script_name;
  std::vector<char*> argv = {program.data(), script.data(), nullptr};
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addchdir_np(&actions, folder.path().c_str());
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  sigset_t blocked, defaults;
  sigemptyset(&blocked);
  sigaddset(&blocked, SIGINT);
  sigaddset(&blocked, SIGHUP);
  sigemptyset(&defaults);
  sigaddset(&defaults, SIGTERM);
  posix_spawnattr_setsigmask(&attributes, &blocked);
  posix_spawnattr_setsigdefault(&attributes, &defaults);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
  const int error = posix_spawnp(pid, "gnuplot", &actions, &attributes, argv.data(), environ);
  posix_spawnattr_destroy(&attributes);
  posix_spawn_file_actions_destroy(&actions);
  return error;
}

// Waits for `pid`; a signal to mechflow while it runs (InterruptCount moves
// past `seen`) stops it: SIGTERM, then SIGKILL after a second. Returns the
// child's wait status, and in `*stopped_by` the signal that stopped it, or 0.
int WaitUnlessInterrupted(pid_t pid, int seen, int* stopped_by) {
  using Clock = std::chrono::steady_clock;
  const auto poll = std::chrono::milliseconds(5);
  int status = 0;
  Clock::time_point kill_at{};
  *stopped_by = 0;
  for (;;) {
    const pid_t r = waitpid(pid, &status, WNOHANG);
    if (r == pid || (r < 0 && errno != EINTR)) {
      // a signal that reached gnuplot too (a terminal's Ctrl-C goes to the
      // whole group) may end it before this loop saw the signal: it came
      // while gnuplot drew all the same
      if (!*stopped_by && InterruptCount() != seen) *stopped_by = *InterruptFlag();
      return status;
    }
    if (!*stopped_by && InterruptCount() != seen) {
      *stopped_by = *InterruptFlag();
      kill(pid, SIGTERM);
      kill_at = Clock::now() + std::chrono::seconds(1);
    } else if (*stopped_by && Clock::now() >= kill_at) {
      kill(pid, SIGKILL);
      kill_at = Clock::time_point::max();
    }
    std::this_thread::sleep_for(poll);
  }
}

}  // namespace

std::string DrawPlot(const std::string& script, const OutputFolder& folder, const std::string& plot_name) {
  const InterruptHandlers handlers;  // when the command has none (psd): a signal stops gnuplot, not mechflow
  const std::string plot_path = folder.PathOf(plot_name);
  if (g_plots_stopped_by)
    throw Interrupted(g_plots_stopped_by, "no plot '" + plot_path + "': plots were stopped by " +
                                              SignalName(g_plots_stopped_by));
  std::string script_name = plot_name + ".gp";
  folder.Write(script_name, script);
  folder.Clear(plot_name);  // so that a plot there afterwards is gnuplot's
  // gnuplot runs in the output folder, so that the script names only the
  // plain file names of the diagram
  const int seen = InterruptCount();
  pid_t pid = 0;
  const int error = StartGnuplot(folder, script_name, &pid);
  if (error == ENOENT) return "gnuplot not found (install it: apt-get install gnuplot-nox)";
  if (error != 0) return std::string("cannot start gnuplot: ") + std::strerror(error);
  int stopped_by = 0;
  const int status = WaitUnlessInterrupted(pid, seen, &stopped_by);
  if (stopped_by) {
    folder.RemoveCut(plot_name);
    g_plots_stopped_by = stopped_by;
    throw Interrupted(stopped_by, "no plot '" + plot_path + "': " + SignalName(stopped_by) +
                                      " came while gnuplot drew it, which was stopped");
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    folder.RemoveCut(plot_name);
    throw WriteError("gnuplot failed on '" + folder.PathOf(script_name) + "' (its messages are above)");
  }
  if (!folder.HasFile(plot_name))
    throw WriteError("gnuplot made no '" + plot_path + "' (is the disk full?)");
  if (const std::string missing = MissingEnd(plot_path); !missing.empty()) {
    folder.RemoveCut(plot_name);
    throw WriteError("gnuplot's plot '" + plot_path + "' is cut: " + missing +
                     " (is the disk full?); the incomplete file is removed");
  }
  return "";
}

}  // namespace mechflow::cli
