#include "cli/xy_plot.h"

#include <algorithm>
#include <filesystem>
#include <sstream>

#include "cli/gnuplot_text.h"

namespace mechflow::cli {

std::string XYPlotScript(const std::vector<XYPanel>& panels, const std::string& title, const std::string& csv_name,
                         const std::string& plot_name) {
  const bool svg = std::filesystem::path(plot_name).extension() == ".svg";
  const int count = std::max<int>(1, static_cast<int>(panels.size()));
  const int height = std::min(4000, 120 + 380 * count);
  std::ostringstream s;
  s << "# drawn by mechflow; edit and run again in this folder with: gnuplot " << GnuplotQuote(plot_name + ".gp")
    << "\n";
  s << "set terminal " << (svg ? "svg" : "pngcairo") << " size 1000," << height << " noenhanced font 'sans,10'"
    << (svg ? " background rgb 'white'" : "") << "\n";
  s << "set output " << GnuplotQuote(plot_name) << "\n";
  s << "set datafile separator ','\n";
  s << "set grid\nset key outside right top\nset lmargin 12\nset rmargin 28\n";
  s << "set multiplot layout " << count << ",1 title " << GnuplotQuote(title) << "\n";
  for (const XYPanel& p : panels) {
    s << "set title " << GnuplotQuote(p.title) << "\n";
    s << "set xlabel " << GnuplotQuote(p.x_label) << "\nset ylabel " << GnuplotQuote(p.y_label) << "\n";
    s << (p.log_x ? "set logscale x\n" : "unset logscale x\n") << (p.log_y ? "set logscale y\n" : "unset logscale y\n");
    if (p.x_max > 0) s << "set xrange [:" << p.x_max << "]\n";
    else s << "set xrange [*:*]\n";
    s << "plot ";
    for (std::size_t i = 0; i < p.curves.size(); ++i) {
      const XYCurve& c = p.curves[i];
      s << (i ? ", \\\n     " : "") << (i ? "''" : GnuplotQuote(csv_name)) << " using " << c.x_column + 1 << ":"
        << c.y_column + 1 << " every ::1 with " << (c.points ? "linespoints pt 7 ps 0.8" : "lines") << " lw 1.5 title "
        << GnuplotQuote(c.title);
    }
    if (p.curves.empty()) s << "[0:1] 0 notitle";
    s << "\n";
  }
  s << "unset multiplot\n";
  return s.str();
}

}  // namespace mechflow::cli
