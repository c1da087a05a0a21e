#include "blocks/outputs/column_names.h"

namespace mechflow::blocks {

std::vector<std::string> LoggedColumnNames(const std::vector<SignalRef>& logged) {
  std::vector<std::string> names;
  for (const SignalRef& s : logged)
    for (int i = 0; i < s.width; ++i) names.push_back(s.width == 1 ? s.name : s.name + "[" + std::to_string(i) + "]");
  return names;
}

}  // namespace mechflow::blocks
