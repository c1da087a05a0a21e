#include "bench/friction_diagram.h"

#include <sstream>
#include <stdexcept>

namespace mechflow::bench {

std::string FrictionLineDiagram(const FrictionLine& line, const std::vector<double>& x0, const std::vector<double>& v0,
                                const DiagramSettings& settings) {
  const int n = line.size();
  if (n < 1 || static_cast<int>(x0.size()) != n || static_cast<int>(v0.size()) != n)
    throw std::invalid_argument("FrictionLineDiagram: initial state does not fit " + std::to_string(n) + " masses");
  std::ostringstream x;
  x.precision(17);  // the numbers round-trip exactly
  const FrictionLaw& f = line.friction;
  x << "<diagram name=\"friction_line\">\n<mechanism name=\"m\" gravity=\"0 0 -9.81\">\n";
  for (int i = 1; i <= n; ++i) x << "<body name=\"M" << i << "\" mass=\"" << line.masses[i - 1] << "\" inertia=\"1 1 1\"/>\n";
  const bool anchored = line.anchor_stiffness != 0.0 || line.anchor_damping != 0.0;
  const bool leader = anchored && line.anchor_speed != 0.0;
  if (leader) x << "<body name=\"Leader\" mass=\"1\" inertia=\"1 1 1\"/>\n";
  for (int i = 1; i <= n; ++i)
    x << "<joint name=\"x" << i << "\" type=\"translational\" body1=\"Base0\" body2=\"M" << i << "\" point1=\"" << i
      << " 0 0\" axis=\"1 0 0\" q0=\"" << x0[i - 1] << "\" v0=\"" << v0[i - 1] << "\"/>\n";
  if (leader)
    x << "<joint name=\"jLeader\" type=\"generalized\" body1=\"Base0\" body2=\"Leader\">"
      << "<et type=\"tt\" axis=\"1 0 0\" value=\"" << line.anchor_speed << "*t\"/></joint>\n";
  if (anchored)
    x << "<force name=\"anchor\" type=\"linear\" body1=\"" << (leader ? "Leader" : "Base0") << "\" body2=\"M1\" c=\""
      << line.anchor_stiffness << "\" d=\"" << line.anchor_damping << "\"/>\n";
  for (int i = 2; i <= n; ++i)
    x << "<force name=\"s" << i << "\" type=\"linear\" body1=\"M" << i - 1 << "\" body2=\"M" << i << "\" c=\""
      << line.stiffness << "\" d=\"" << line.damping << "\"/>\n";
  for (int i = 1; i <= n; ++i)
    x << "<force name=\"f" << i << "\" type=\"frictional\" body1=\"Base0\" point1=\"" << i - 1
      << " 0 0\" body2=\"M" << i << "\" friction=\"" << f.friction << "\" ratio=\"" << f.ratio << "\" c=\""
      << f.stiffness << "\" d=\"" << f.damping << "\"/>\n";
  if (line.force_amplitude != 0.0)
    x << "<applied_force name=\"push\" body=\"M" << n << "\" force=\"" << line.force_amplitude << "*sin(2*pi*"
      << line.force_frequency << "*t) 0 0\"/>\n";
  for (int i = 1; i <= n; ++i)
    x << "<sensor name=\"x" << i << "\" kind=\"coordinate\" dof=\"x" << i << "\"/><sensor name=\"v" << i
      << "\" kind=\"velocity\" dof=\"x" << i << "\"/>\n";
  x << "</mechanism>\n<solver t_end=\"" << settings.t_end << "\" rtol=\"" << settings.rtol << "\" atol=\""
    << settings.atol << "\"/>\n<output interval=\"" << settings.t_end / settings.num_outputs << "\">\n";
  for (int i = 1; i <= n; ++i) x << "<log signal=\"m.x" << i << "\"/><log signal=\"m.v" << i << "\"/>\n";
  x << "</output>\n</diagram>\n";
  return x.str();
}

}  // namespace mechflow::bench
