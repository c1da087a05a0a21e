#include "cli/modes_report.h"

#include <cmath>
#include <cstdio>
#include <fstream>

#include "mech/errors.h"

namespace mechflow::cli {

void PrintModes(const std::vector<blocks::Mode>& modes, const std::vector<std::string>& states,
                const std::vector<double>& x, bool at_equilibrium, std::ostream& out) {
  out << (at_equilibrium ? "linearised at the static equilibrium:\n" : "linearised at the initial state:\n");
  char line[256];
  for (std::size_t i = 0; i < states.size(); ++i) {
    std::snprintf(line, sizeof line, "  %-28s %14.8g\n", states[i].c_str(), x[i]);
    out << line;
  }
  out << "\n mode   f damped [Hz]   f natural [Hz]   damping ratio    Re lambda [1/s]   Im lambda [rad/s]\n";
  for (std::size_t k = 0; k < modes.size(); ++k) {
    const blocks::Mode& m = modes[k];
    std::snprintf(line, sizeof line, " %4zu %15.6f %16.6f %15.6f %18.6g %19.6g\n", k + 1, m.frequency_hz,
                  m.natural_frequency_hz, m.damping_ratio, m.eigenvalue.real(), m.eigenvalue.imag());
    out << line;
  }
  out << "\nmode shapes (components of magnitude >= 1e-3, largest = 1):\n";
  for (std::size_t k = 0; k < modes.size(); ++k) {
    out << " mode " << k + 1 << ":";
    for (std::size_t i = 0; i < states.size(); ++i)
      if (std::abs(modes[k].shape[i]) >= 1e-3) {
        std::snprintf(line, sizeof line, " %s %.4g", states[i].c_str(), modes[k].shape[i]);
        out << line;
      }
    out << "\n";
  }
}

void WriteModesCsv(const std::vector<blocks::Mode>& modes, const std::vector<std::string>& states,
                   const std::string& path) {
  std::ofstream csv(path);
  if (!csv) throw InputError("cannot write '" + path + "'");
  csv.precision(17);
  csv << "mode,frequency_hz,natural_frequency_hz,damping_ratio,lambda_re,lambda_im";
  for (const auto& s : states) csv << "," << s;
  csv << "\n";
  for (std::size_t k = 0; k < modes.size(); ++k) {
    const blocks::Mode& m = modes[k];
    csv << k + 1 << "," << m.frequency_hz << "," << m.natural_frequency_hz << "," << m.damping_ratio << ","
        << m.eigenvalue.real() << "," << m.eigenvalue.imag();
    for (double v : m.shape) csv << "," << v;
    csv << "\n";
  }
}

}  // namespace mechflow::cli
