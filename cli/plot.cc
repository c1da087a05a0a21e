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
std::string GnuplotScript(const blocks::Results& results, const std::vector<diagrams::PlotGroup>& groups,
                          const std::string& title, const std::string& csv_name, const std::string& plot_name,
                          const std::vector<diagrams::XYPlotRequest>& xy) {
  std::ostringstream s;
  s << GnuplotPreamble(plot_name, static_cast<int>(groups.size() + xy.size()), 260, 22, title)
    << "set xlabel 'time [s]'\n";
  for (const auto& g : groups) {
    // the group's name on its axis too, with the unit of its columns
    s << "set title " << GnuplotQuote(g.name) << "\nset ylabel " << GnuplotQuote(g.axis_label) << "\n";
    s << "plot ";
    for (size_t i = 0; i < g.columns.size(); ++i) {
      const int c = g.columns[i];
      s << (i ? ", \\\n     " : "") << (i ? "''" : GnuplotQuote(csv_name)) << " using 1:" << (c + 1)
        << " every ::1 with lines lw 1.5 title " << GnuplotQuote(results.columns()[c]);
    }
    s << "\n";
  }
  for (const diagrams::XYPlotRequest& p : xy) {
    s << "set title " << GnuplotQuote(p.title) << "\nset xlabel " << GnuplotQuote(p.x_label) << "\nset ylabel "
      << GnuplotQuote(p.y_label) << "\nplot ";
    for (std::size_t i = 0; i < p.curves.size(); ++i) {
      const auto [x, y] = p.curves[i];
      s << (i ? ", \\\n     " : "") << (i ? "''" : GnuplotQuote(csv_name)) << " using " << x + 1 << ":" << y + 1
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
  std::ostringstream s;
  s << GnuplotPreamble(plot_name, static_cast<int>(groups.size()), 300, 28, title) << "set xlabel 'time [s]'\n";
  for (const auto& g : groups) {
    s << "set title " << GnuplotQuote(g.name) << "\nset ylabel " << GnuplotQuote(g.axis_label) << "\nplot ";
    bool first = true;
    for (const OverlayRun& run : runs)
      for (const int c : g.columns) {
        const std::string label = g.columns.size() > 1 ? run.label + " " + columns[c] : run.label;
        s << (first ? "" : ", \\\n     ") << GnuplotQuote(run.csv_name) << " using 1:" << c + 1
          << " every ::1 with lines lw 1.5 title " << GnuplotQuote(label);
        first = false;
      }
    if (first) s << "[0:1] 0 notitle";
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
