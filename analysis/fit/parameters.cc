#include "analysis/fit/parameters.h"

#include <charconv>
#include <cmath>

#include "blocks/support/excerpt.h"
#include "mech/errors.h"

namespace mechflow::analysis::fit {
namespace {

double Number(const std::string& text, const std::string& what, const std::string& spec) {
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc() || end != text.data() + text.size() || !std::isfinite(value))
    throw InputError("--free " + blocks::Excerpt(spec) + ": the " + what + " bound '" + blocks::Excerpt(text) +
                     "' is not a finite number");
  return value;
}

}  // namespace

double FreeParameter::ToUnit(double value) const {
  return log ? std::log(value / lower) / std::log(upper / lower) : (value - lower) / (upper - lower);
}

double FreeParameter::FromUnit(double u) const {
  return log ? lower * std::pow(upper / lower, u) : lower + u * (upper - lower);
}

double FreeParameter::Slope(double u) const {
  return log ? FromUnit(u) * std::log(upper / lower) : upper - lower;
}

FreeParameter ParseFree(const std::string& text) {
  const auto eq = text.find('=');
  const std::string usage = "; expected NAME=LOWER:UPPER or NAME=LOWER:UPPER:log (bounds are required)";
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
    throw InputError("--free '" + blocks::Excerpt(text) + "'" + usage);
  FreeParameter p;
  p.name = text.substr(0, eq);
  std::vector<std::string> parts;
  for (std::size_t start = eq + 1;;) {
    const std::size_t at = text.find(':', start);
    parts.push_back(text.substr(start, at == std::string::npos ? std::string::npos : at - start));
    if (at == std::string::npos) break;
    start = at + 1;
  }
  if (parts.size() == 3 && parts[2] == "log") p.log = true;
  else if (parts.size() != 2) throw InputError("--free '" + blocks::Excerpt(text) + "'" + usage);
  p.lower = Number(parts[0], "lower", text);
  p.upper = Number(parts[1], "upper", text);
  if (!(p.lower < p.upper))
    throw InputError("--free " + blocks::Excerpt(text) + ": the lower bound must be below the upper bound");
  if (p.log && !(p.lower > 0))
    throw InputError("--free " + blocks::Excerpt(text) + ": a log scale needs bounds > 0");
  return p;
}

std::vector<double> FromUnit(const std::vector<FreeParameter>& parameters, const std::vector<double>& u) {
  std::vector<double> values(parameters.size());
  for (std::size_t j = 0; j < parameters.size(); ++j) values[j] = parameters[j].FromUnit(u[j]);
  return values;
}

}  // namespace mechflow::analysis::fit
