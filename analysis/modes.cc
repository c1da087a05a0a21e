#include "analysis/modes.h"

#include <algorithm>

#include "mech/errors.h"

namespace mechflow::analysis {

ModesAnalysis AnalyseModes(const Diagram& diagram, double t_start, bool equilibrium) {
  if (diagram.num_states() == 0)
    throw InputError("the diagram has no continuous states; nothing to analyse");
  ModesAnalysis a;
  a.time = t_start;
  Context ctx;
  PrepareContext(diagram, a.time, &ctx, &a.x);
  if (equilibrium) a.equilibrium = FindEquilibrium(diagram, &ctx, &a.x);

  const Eigen::MatrixXd A = StateJacobian(diagram, &ctx, a.x);
  a.states = StateNames(diagram);
  a.x.resize(a.states.size());
  a.roles = FindStateRoles(A);
  for (std::size_t i = 0; i < a.states.size(); ++i) {
    if (a.states[i].find(".q:") != std::string::npos) a.roles.coordinate[i] = true;
    if (a.states[i].find(".v:") != std::string::npos) a.roles.rate[i] = true;
  }
  // shapes normalised on the coordinates when there are any, else on every state
  std::vector<bool> normalise_on = a.roles.coordinate;
  if (std::find(normalise_on.begin(), normalise_on.end(), true) == normalise_on.end()) normalise_on.clear();
  a.modes = ModalAnalysis(A, normalise_on);
  a.switching = DescribeLinearisedModes(diagram, ctx);
  return a;
}

}  // namespace mechflow::analysis
