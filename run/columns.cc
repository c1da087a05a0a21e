#include "run/columns.h"

namespace mechflow::run {

std::vector<std::string> ColumnNames(const std::vector<blocks::SignalRef>& logged) {
  std::vector<std::string> names = {"time"};
  for (const blocks::SignalRef& s : logged)
    for (int i = 0; i < s.width; ++i) names.push_back(s.width == 1 ? s.name : s.name + "[" + std::to_string(i) + "]");
  return names;
}

std::string WithUnit(const std::string& label, const std::string& unit) {
  return unit.empty() ? label : label + " [" + unit + "]";
}

}  // namespace mechflow::run
