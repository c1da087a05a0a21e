#include "run/columns.h"

#include <utility>

#include "blocks/outputs/column_names.h"

namespace mechflow::run {

std::vector<std::string> ColumnNames(const std::vector<blocks::SignalRef>& logged) {
  std::vector<std::string> names = {"time"};
  for (std::string& name : blocks::LoggedColumnNames(logged)) names.push_back(std::move(name));
  return names;
}

std::string WithUnit(const std::string& label, const std::string& unit) {
  return unit.empty() ? label : label + " [" + unit + "]";
}

}  // namespace mechflow::run
