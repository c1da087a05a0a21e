#include "cli/fit_output.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "blocks/outputs/csv.h"
#include "cli/gnuplot_text.h"
#include "cli/plot.h"

namespace mechflow::cli {
namespace {

using blocks::CsvField;
using blocks::CsvNumber;

// A number for the terminal: 6 significant digits, NaN as "-".
std::string Short(double v) {
  if (std::isnan(v)) return "-";
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}

std::string Padded(const std::string& s, std::size_t width) {
  return s.size() >= width ? s + " " : s + std::string(width - s.size(), ' ');
}

// NaN (not determined) as an empty field.
std::string Field(double v) { return std::isnan(v) ? "" : CsvNumber(v); }

std::string DataName(const FitReport& r, std::size_t e) {
  return r.stem + ".fit.data" + std::to_string(e + 1) + ".csv";
}

std::string PlotScript(const FitReport& r, const std::string& plot_name) {
  const auto& setup = *r.setup;
  int signals = 0;
  for (const auto& m : setup.matches) signals += m.is_signal();
  const int panels = static_cast<int>(setup.experiments.size()) * signals + 1;
  std::ostringstream s;
  s << GnuplotPreamble(plot_name, panels, 260, 28, r.stem + ": measured and fitted");
  s << "set xlabel 'time [s]'\n";
  for (std::size_t e = 0; e < setup.experiments.size(); ++e) {
    int column = 2;  // time, then measured, fitted, start per signal's match
    for (const auto& m : setup.matches) {
      if (!m.is_signal()) continue;
      const int measured = column;
      column += 3;
      s << "set title " << GnuplotQuote(setup.experiments[e].file + ": " + m.signal) << "\nset ylabel "
        << GnuplotQuote(m.signal) << "\nunset logscale y\nplot " << GnuplotQuote(DataName(r, e)) << " using 1:"
        << measured + 2 << " every ::1 with lines lw 1 " << CurveStyle(11) << " title 'start', \\\n     '' using 1:"
        << measured + 1 << " every ::1 with lines lw 2 " << CurveStyle(0) << " title 'fitted', \\\n     '' using 1:"
        << measured << " every ::1 with points pt 7 ps 0.5 " << CurveStyle(7) << " title "
        << GnuplotQuote("measured " + m.column) << "\n";
    }
  }
  s << "set title 'cost (sum of squared weighted residuals)'\nset xlabel 'step'\nset ylabel 'cost'\n"
       "set logscale y\nplot "
    << GnuplotQuote(r.stem + ".fit.history.csv") << " using 1:2 every ::1 with linespoints pt 7 ps 0.6 lw 1.5 "
    << CurveStyle(0) << " title 'cost'\nunset multiplot\n";
  return s.str();
}

}  // namespace

void PrintFit(const FitReport& report, std::ostream& out) {
  const auto& setup = *report.setup;
  const auto& r = *report.result;
  out << Padded("parameter", 14) << Padded("value", 14) << Padded("std. error", 14) << Padded("start", 14)
      << Padded("lower", 12) << Padded("upper", 12) << "\n";
  for (std::size_t j = 0; j < setup.parameters.size(); ++j) {
    const auto& p = setup.parameters[j];
    out << Padded(p.name, 14) << Padded(Short(r.values[j]), 14)
        << Padded(Short(r.statistics.standard_error[j]), 14) << Padded(Short(r.start[j]), 14)
        << Padded(Short(p.lower), 12) << Padded(Short(p.upper), 12) << (p.log ? "log " : "")
        << (r.at_bound[j] ? "AT A BOUND" : "") << "\n";
  }
  if (setup.parameters.size() > 1) {
    out << "correlation:\n" << Padded("", 14);
    for (const auto& p : setup.parameters) out << Padded(p.name, 10);
    out << "\n";
    for (std::size_t i = 0; i < setup.parameters.size(); ++i) {
      out << Padded(setup.parameters[i].name, 14);
      for (std::size_t j = 0; j < setup.parameters.size(); ++j)
        out << Padded(std::isnan(r.statistics.correlation(i, j)) ? "-" : Short(std::round(r.statistics.correlation(i, j) * 1e4) / 1e4), 10);
      out << "\n";
    }
  }
  for (std::size_t e = 0; e < setup.experiments.size(); ++e)
    for (std::size_t k = 0; k < setup.matches.size(); ++k)
      if (!setup.matches[k].is_signal())
        out << setup.experiments[e].file << ": " << setup.matches[k].signal << ": measured "
            << Short(setup.experiments[e].measured[k][0]) << ", start " << Short(r.initial.simulated[e][k][0])
            << ", fitted " << Short(r.fitted.simulated[e][k][0]) << "\n";
  out << "cost (sum of squared weighted residuals, " << r.residuals << " of them): before " << Short(r.cost_before)
      << ", after " << Short(r.cost_after) << "\n";
}

std::vector<std::string> WriteFit(const FitReport& report, const std::string& summary, const OutputFolder& folder, bool plot,
                                  std::string* plot_warning) {
  const auto& setup = *report.setup;
  const auto& r = *report.result;
  std::vector<std::string> written;
  const auto write = [&](const std::string& name, const std::string& text) {
    folder.Write(name, text);
    written.push_back(name);
  };
  std::ostringstream table;
  table << "parameter,value,standard_error,lower,upper,at_bound\n";
  for (std::size_t j = 0; j < setup.parameters.size(); ++j) {
    const auto& p = setup.parameters[j];
    table << CsvField(p.name) << "," << CsvNumber(r.values[j]) << "," << Field(r.statistics.standard_error[j]) << ","
          << CsvNumber(p.lower) << "," << CsvNumber(p.upper) << "," << (r.at_bound[j] ? "yes" : "no") << "\n";
  }
  write(report.stem + ".fit.csv", table.str());
  write(report.stem + ".fit.txt", summary);

  std::ostringstream set;
  set << "# fitted by mechflow fit " << report.diagram << "; use with: mechflow run " << report.diagram
      << " --set-file " << report.stem << ".fit.set\n";
  for (std::size_t j = 0; j < setup.parameters.size(); ++j)
    set << setup.parameters[j].name << "=" << CsvNumber(r.values[j]) << "\n";
  write(report.stem + ".fit.set", set.str());

  std::ostringstream correlation;
  correlation << "parameter";
  for (const auto& p : setup.parameters) correlation << "," << CsvField(p.name);
  correlation << "\n";
  for (std::size_t i = 0; i < setup.parameters.size(); ++i) {
    correlation << CsvField(setup.parameters[i].name);
    for (std::size_t j = 0; j < setup.parameters.size(); ++j) correlation << "," << Field(r.statistics.correlation(i, j));
    correlation << "\n";
  }
  write(report.stem + ".fit.correlation.csv", correlation.str());

  std::ostringstream history;
  history << "iteration,cost\n";
  for (std::size_t i = 0; i < r.optimiser.history.size(); ++i) history << i << "," << CsvNumber(r.optimiser.history[i]) << "\n";
  write(report.stem + ".fit.history.csv", history.str());

  for (std::size_t e = 0; e < setup.experiments.size(); ++e) {
    const auto& experiment = setup.experiments[e];
    std::ostringstream data;
    data << "time";
    for (const auto& m : setup.matches)
      if (m.is_signal())
        data << "," << CsvField(m.column + " measured") << "," << CsvField(m.signal + " fitted") << ","
             << CsvField(m.signal + " start");
    data << "\n";
    for (std::size_t i = 0; i < experiment.times.size(); ++i) {
      data << CsvNumber(experiment.times[i]);
      for (std::size_t k = 0; k < setup.matches.size(); ++k)
        if (setup.matches[k].is_signal())
          data << "," << CsvNumber(experiment.measured[k][i]) << "," << Field(r.fitted.simulated[e][k][i]) << ","
               << Field(r.initial.simulated[e][k][i]);
      data << "\n";
    }
    write(DataName(report, e), data.str());
  }
  if (plot) {
    const std::string name = report.stem + ".fit.png";
    *plot_warning = DrawPlot(PlotScript(report, name), folder, name);
    if (plot_warning->empty()) written.push_back(name);
  }
  return written;
}

}  // namespace mechflow::cli
