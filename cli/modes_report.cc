#include "cli/modes_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>

#include "blocks/support/message_number.h"
#include "mech/errors.h"

namespace mechflow::cli {
namespace {

using blocks::Formatted;

// Modes per block of columns in the mode-shape table.
constexpr std::size_t kShapeColumns = 6;

std::string Role(const analysis::StateRoles& roles, std::size_t i) {
  const bool coordinate = i < roles.coordinate.size() && roles.coordinate[i];
  const bool rate = i < roles.rate.size() && roles.rate[i];
  if (coordinate && rate) return "coordinate, rate";
  if (coordinate) return "coordinate";
  if (rate) return "rate";
  return "";
}

std::string Kind(const analysis::Mode& m) {
  switch (m.kind) {
    case analysis::ModeKind::kOscillating:
      return m.damping_ratio < 0 ? "oscillating, growing" : "oscillating";
    case analysis::ModeKind::kDecaying:
      return "decaying at " + Formatted("%.6g", m.decay_rate) + " 1/s (time constant " +
             Formatted("%.6g", 1 / m.decay_rate) + " s)";
    case analysis::ModeKind::kGrowing:
      return "growing at " + Formatted("%.6g", -m.decay_rate) + " 1/s (unstable)";
    case analysis::ModeKind::kRigidBody:
      return "rigid-body (free motion)";
  }
  return "";
}

}  // namespace

void PrintModes(const ModesReport& r, std::ostream& out) {
  std::size_t width = 5;
  for (const auto& s : r.states) width = std::max(width, s.size());
  char line[512];

  // where
  out << "linearised at " << (r.equilibrium ? "the static equilibrium" : "the initial state") << ", t = " << r.time
      << " s";
  if (r.equilibrium)
    out << " (found in " << r.equilibrium->iterations << " Newton step" << (r.equilibrium->iterations == 1 ? "" : "s")
        << ", largest rate " << r.equilibrium->residual << ")";
  out << "\n";
  if (r.equilibrium && r.equilibrium->rounds > 1) {
    // the modes below are the equilibrium's, not the initial state's
    out << "modes selected again at each rest state found (" << r.equilibrium->rounds << " rounds)";
    std::string names;
    for (const std::string& s : r.equilibrium->switched) names += (names.empty() ? "" : ", ") + s;
    out << (names.empty() ? "; none differs from the initial state's" : "; switched from the initial state's: " + names)
        << "\n";
  }
  std::snprintf(line, sizeof line, "  %-*s %16s  %s\n", static_cast<int>(width), "state", "value", "role");
  out << line;
  for (std::size_t i = 0; i < r.states.size(); ++i) {
    std::snprintf(line, sizeof line, "  %-*s %16.9g  %s\n", static_cast<int>(width), r.states[i].c_str(), r.x[i],
                  Role(r.roles, i).c_str());
    out << line;
  }

  // what the switching elements were taken as: the modes hold only while they last
  if (!r.switching.empty()) {
    out << "\nswitching elements, linearised in their modes at this state (the frequencies below hold only "
           "while these modes last):\n";
    for (const std::string& s : r.switching) out << "  " << s << "\n";
  }

  // frequencies
  out << "\n mode   f damped [Hz]   f natural [Hz]   damping ratio   Re lambda [1/s]   Im lambda [rad/s]   kind\n";
  for (std::size_t k = 0; k < r.modes.size(); ++k) {
    const analysis::Mode& m = r.modes[k];
    std::snprintf(line, sizeof line, " %4zu %15.6f %16.6f %15.6f %17.6g %19.6g   %s\n", k + 1, m.frequency_hz,
                  m.natural_frequency_hz, m.damping_ratio, m.eigenvalue.real(), m.eigenvalue.imag(),
                  Kind(m).c_str());
    out << line;
  }

  // shapes, a block of columns at a time
  const bool any_coordinate = std::find(r.roles.coordinate.begin(), r.roles.coordinate.end(), true) !=
                              r.roles.coordinate.end();
  out << "\nmode shapes (real part of the eigenvector, scaled so that its largest "
      << (any_coordinate ? "coordinate" : "component") << " is 1";
  if (any_coordinate) out << ";\na rate's component is lambda times its coordinate's: 0 in an undamped mode";
  out << "):\n";
  for (std::size_t first = 0; first < r.modes.size(); first += kShapeColumns) {
    const std::size_t last = std::min(r.modes.size(), first + kShapeColumns);
    std::snprintf(line, sizeof line, "  %-*s %-11s", static_cast<int>(width), "state", "role");
    out << line;
    for (std::size_t k = first; k < last; ++k) {
      std::snprintf(line, sizeof line, " %11s", ("mode " + std::to_string(k + 1)).c_str());
      out << line;
    }
    out << "\n";
    for (std::size_t i = 0; i < r.states.size(); ++i) {
      std::snprintf(line, sizeof line, "  %-*s %-11s", static_cast<int>(width), r.states[i].c_str(),
                    Role(r.roles, i) == "coordinate, rate" ? "coord, rate" : Role(r.roles, i).c_str());
      out << line;
      for (std::size_t k = first; k < last; ++k) {
        const double c = r.modes[k].shape[i];
        std::snprintf(line, sizeof line, " %11.5g", std::abs(c) < 1e-9 ? 0.0 : c);
        out << line;
      }
      out << "\n";
    }
    if (last < r.modes.size()) out << "\n";
  }
}

void WriteModesCsv(const std::vector<analysis::Mode>& modes, const std::vector<std::string>& states,
                   std::ostream& csv) {
  csv.precision(17);
  csv << "mode,frequency_hz,natural_frequency_hz,damping_ratio,lambda_re,lambda_im";
  for (const auto& s : states) csv << "," << s;
  csv << "\n";
  for (std::size_t k = 0; k < modes.size(); ++k) {
    const analysis::Mode& m = modes[k];
    csv << k + 1 << "," << m.frequency_hz << "," << m.natural_frequency_hz << "," << m.damping_ratio << ","
        << m.eigenvalue.real() << "," << m.eigenvalue.imag();
    for (double v : m.shape) csv << "," << v;
    csv << "\n";
  }
}

}  // namespace mechflow::cli
