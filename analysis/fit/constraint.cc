#include "analysis/fit/constraint.h"

#include "blocks/outputs/csv.h"
#include "blocks/support/excerpt.h"
#include "mech/errors.h"
#include "scripting/identifiers.h"

namespace mechflow::analysis::fit {
namespace {

std::string Trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t"), last = s.find_last_not_of(" \t");
  return first == std::string::npos ? "" : s.substr(first, last - first + 1);
}

}  // namespace

Constraint ParseConstraint(const std::string& text, const std::vector<FreeParameter>& parameters) {
  const std::string usage = "--constraint '" + blocks::Excerpt(text) +
                            "': expected A<=B or A>=B, A and B free parameters (--free)";
  auto at = text.find("<=");
  bool less = true;
  if (at == std::string::npos) {
    at = text.find(">=");
    less = false;
  }
  if (at == std::string::npos) throw InputError(usage);
  const std::string a = Trim(text.substr(0, at)), b = Trim(text.substr(at + 2));
  const auto index = [&](const std::string& name) {
    for (std::size_t j = 0; j < parameters.size(); ++j)
      if (scripting::ToLower(parameters[j].name) == scripting::ToLower(name)) return static_cast<int>(j);
    throw InputError(usage + "; '" + blocks::Excerpt(name) + "' is not one");
  };
  Constraint c;
  c.text = text;
  c.lower = index(less ? a : b);
  c.upper = index(less ? b : a);
  if (c.lower == c.upper) throw InputError(usage + "; it names one parameter twice");
  return c;
}

std::string Broken(const std::vector<Constraint>& constraints, const std::vector<FreeParameter>& parameters,
                   const std::vector<double>& values) {
  for (const Constraint& c : constraints)
    if (!(values[c.lower] <= values[c.upper]))
      return parameters[c.lower].name + "=" + blocks::CsvNumber(values[c.lower]) + " above " +
             parameters[c.upper].name + "=" + blocks::CsvNumber(values[c.upper]) + " breaks --constraint " + c.text;
  return "";
}

}  // namespace mechflow::analysis::fit
