#pragma once
// The modal analysis of a diagram, as `mechflow modes` reports it and the
// Python module returns it: where it was linearised, the states' names and
// roles, the modes sorted by natural frequency, and what the switching
// elements were taken as (analysis/linearization.h has the steps).

#include <optional>
#include <string>
#include <vector>

#include "analysis/linearization.h"

namespace mechflow::analysis {

struct ModesAnalysis {
  double time = 0.0;                         // [s], where the diagram was linearised (t_start)
  std::optional<EquilibriumResult> equilibrium;  // set when linearised at a found equilibrium
  std::vector<std::string> states;           // "block.state", in state order
  std::vector<double> x;                     // the state linearised at
  StateRoles roles;                          // coordinates and rates, per state
  std::vector<Mode> modes;                   // sorted by natural frequency
  std::vector<std::string> switching;        // DescribeLinearisedModes
};

// Linearises `diagram` at t_start, at its initial state or (`equilibrium`) at
// the static equilibrium found from it; coordinates (a state whose rate is
// another state, or a mechanism's q) carry the mode shapes. The diagram must
// have continuous states (InputError otherwise); SimulationError when the
// equilibrium is not found.
ModesAnalysis AnalyseModes(const Diagram& diagram, double t_start, bool equilibrium);

}  // namespace mechflow::analysis
