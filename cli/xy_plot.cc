#include "cli/xy_plot.h"

#include <algorithm>
#include <filesystem>
#include <sstream>

#include "cli/gnuplot_text.h"

namespace mechflow::cli {

std::string XYPlotScript(const std::vector<XYPanel>& panels, const std::string& title, const std::string& csv_name,
                         const std::string& plot_name) {
  std::ostringstream s;
  s << GnuplotPreamble(plot_name, static_cast<int>(panels.size()), 380, 28, title);
  for (const XYPanel& p : panels) {
    s << "set title " << GnuplotQuote(p.title) << "\n";
    s << "set xlabel " << GnuplotQuote(p.x_label) << "\nset ylabel " << GnuplotQuote(p.y_label) << "\n";
    s << (p.log_x ? "set logscale x\n" : "unset logscale x\n") << (p.log_y ? "set logscale y\n" : "unset logscale y\n");
    if (p.x_max > 0) s << "set xrange [:" << p.x_max << "]\n";
    else s << "set xrange [*:*]\n";
    s << (p.y_includes_zero ? "set yrange [*<0:0<*]\n" : "set yrange [*:*]\n");
    s << "plot ";
    for (std::size_t i = 0; i < p.curves.size(); ++i) {
      const XYCurve& c = p.curves[i];
      s << (i ? ", \\\n     " : "") << (i ? "''" : GnuplotQuote(csv_name)) << " using " << c.x_column + 1 << ":"
        << c.y_column + 1 << " every ::1 with " << (c.points ? "linespoints pt 7 ps 0.8" : "lines") << " lw 1.5 "
        << CurveStyle(static_cast<int>(i)) << " title " << GnuplotQuote(c.title);
    }
    if (p.curves.empty()) s << "[0:1] 0 notitle";
    s << "\n";
  }
  s << "unset multiplot\n";
  return s.str();
}

}  // namespace mechflow::cli
