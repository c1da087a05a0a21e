#include "diagrams/unit_check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>

#include "diagrams/evaluator.h"
#include "diagrams/expression_dimension.h"
#include "mech/errors.h"

namespace mechflow::diagrams {
namespace {

// "file:line: rest" -> "file:line: warning: rest"
std::string AsWarning(const std::string& message) {
  std::size_t colon = message.find(": ");
  return colon == std::string::npos ? "warning: " + message
                                    : message.substr(0, colon) + ": warning: " + message.substr(colon + 2);
}

// Unit names with an angle in them (a rate in them is angular).
constexpr const char* kAngleUnits[] = {"rpm", "rad", "deg", "rev", "\u00b0", "arc"};

std::string Shortest(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.10g", value);
  return text;
}

}  // namespace

std::optional<Dimension> UnitCheck::DimensionOf(const std::string& name) const {
  const int i = ids_->Find(name);
  if (i < 0 || i >= static_cast<int>(units_.size()) || !units_[i]) return std::nullopt;
  return units_[i]->dimension;
}

void UnitCheck::CheckAttribute(const std::string& text, const std::string& attribute, const std::string& si_unit,
                               const std::string& what) const {
  if (si_unit.empty()) return;
  std::string error;
  const std::optional<Unit> expected = ParseUnit(si_unit, &error);
  if (!expected) throw std::logic_error("attribute unit '" + si_unit + "': " + error);
  const std::string t = Trim(text);
  const int id = ids_->Find(t);
  if (id >= 0 && scripting::IsLuaName(t)) {
    if (id >= static_cast<int>(units_.size()) || !units_[id]) return;
    const Unit& unit = *units_[id];
    if (unit.dimension.SameAs(expected->dimension)) return WarnTurnsForCycles(t, id, attribute, si_unit, what);
    throw InputError(what + ": '" + t + "' is " + unit.dimension.Describe() + " in " + unit.text + " (" +
                     ids_->origin(id) + "), used as '" + attribute + "' (" + si_unit + "); give '" + t +
                     "' a unit of " + expected->dimension.Describe() + " or use another identifier");
  }
  const ExpressionDimension found = InferDimension(t, [&](const std::string& n) { return DimensionOf(n); });
  if (!found.conflict.empty())
    Warn(AsWarning(what + ": '" + t + "' " + found.conflict + " (numbers in expressions are SI values)"));
  else if (found.known && !found.plain_number && !found.dimension.SameAs(expected->dimension))
    Warn(AsWarning(what + ": '" + t + "' is " + found.dimension.Describe() + " (" + found.dimension.Text() +
                   ") by the units of its identifiers, used as '" + attribute + "' (" + si_unit + ")"));
}

// A radian counts as 1 in SI, so an angular rate (rpm, rad/s, deg/s) and a
// frequency (Hz) share a dimension, and one given for the other is taken
// as it is in SI: 60 rpm (6.28 rad/s) as a frequency is 6.28 Hz, not the
// 1 Hz of one turn a cycle. Seldom meant: a warning.
void UnitCheck::WarnTurnsForCycles(const std::string& name, int id, const std::string& attribute,
                                   const std::string& si_unit, const std::string& what) const {
  const std::string& text = units_[id]->text;
  const bool angular = std::any_of(std::begin(kAngleUnits), std::end(kAngleUnits),
                                   [&](const char* a) { return text.find(a) != std::string::npos; });
  const double si = ids_->value(id);
  const std::string given = "'" + name + "' is " + Shortest(si / ids_->to_si(id)) + " " + text;
  if (si_unit == "Hz" && angular)
    Warn(AsWarning(what + ": " + given + ", an angular rate (" + Shortest(si) + " rad/s), used as '" + attribute +
                   "' (Hz): taken as " + Shortest(si) + " Hz, not the " + Shortest(si / (2 * M_PI)) +
                   " Hz of one turn a cycle; give it in Hz, or divide by 2*pi"));
  else if (si_unit == "rad/s" && text.find("Hz") != std::string::npos)
    Warn(AsWarning(what + ": " + given + ", a frequency, used as '" + attribute + "' (rad/s): taken as " +
                   Shortest(si) + " rad/s, not the " + Shortest(si * 2 * M_PI) +
                   " rad/s of one turn a cycle; give it in rpm or rad/s, or multiply by 2*pi"));
}

void UnitCheck::CheckDefinitions() const {
  for (int i = 0; i < ids_->size(); ++i) {
    if (!ids_->is_expression(i)) continue;
    // an identifier sees only those above it
    const auto dimension_of = [&](const std::string& n) -> std::optional<Dimension> {
      const int j = ids_->Find(n);
      return j >= 0 && j < i ? DimensionOf(n) : std::nullopt;
    };
    const ExpressionDimension found = InferDimension(ids_->definition(i), dimension_of);
    const std::string who = ids_->origin(i) + ": warning: identifier '" + ids_->spelling(i) + "' = '" +
                            ids_->definition(i) + "'";
    if (!found.conflict.empty()) {
      Warn(who + " " + found.conflict + " (numbers in expressions are SI values)");
      continue;
    }
    if (!found.known || !units_[i]) continue;
    if (found.plain_number) {
      // SI, like every expression: "2*100" with unit mm is 200 m
      if (units_[i]->to_si != 1.0)
        Warn(who + " is computed in SI (numbers in expressions are SI values), so it is " +
             Shortest(ids_->value(i) / units_[i]->to_si) + " " + units_[i]->text +
             "; write the number alone to give it in " + units_[i]->text);
      continue;
    }
    if (found.dimension.SameAs(units_[i]->dimension)) continue;
    Warn(who + " is " + found.dimension.Describe() + " (" + found.dimension.Text() +
         ") by the units of its identifiers, but its unit is " + units_[i]->text + " (" +
         units_[i]->dimension.Describe() + ")");
  }
}

void UnitCheck::Warn(const std::string& warning) const {
  if (std::find(warnings_.begin(), warnings_.end(), warning) == warnings_.end()) warnings_.push_back(warning);
}

}  // namespace mechflow::diagrams
