#pragma once
// UnitCheck: the units of a diagram's identifiers, and the checks of their
// uses against what an attribute is (diagrams/attribute_units.h).
//
// An identifier written as the whole value of an attribute of known unit
// must have that dimension: `mass="L"` with L in mm is bad input naming both
// lines. An expression whose dimension follows from its identifiers' units
// (diagrams/expression_dimension.h) and disagrees -- with the attribute, or
// with the unit its identifier declares -- is a warning naming the line:
// numbers in expressions are SI values, so it may be meant.

#include <optional>
#include <string>
#include <vector>

#include "diagrams/units.h"
#include "scripting/identifiers.h"

namespace mechflow::diagrams {

class UnitCheck {
 public:
  // `units`: the parsed unit of each identifier of `ids` (nullopt: none given).
  UnitCheck(const scripting::IdentifierTable* ids, std::vector<std::optional<Unit>> units)
      : ids_(ids), units_(std::move(units)) {}

  // The dimension of identifier `name` (any case), when it has a unit.
  std::optional<Dimension> DimensionOf(const std::string& name) const;

  // `text` (one value, no list) used as `attribute`, whose SI unit is
  // `si_unit` ("" unknown: nothing to check); `what` starts messages
  // ("d.xml:12: body 'b' attribute 'mass'"). Throws InputError for an
  // identifier of another dimension; notes a warning for an expression.
  void CheckAttribute(const std::string& text, const std::string& attribute, const std::string& si_unit,
                      const std::string& what) const;

  // Warnings for identifiers defined by expressions whose dimension is not
  // that of their declared unit (or that add unlike quantities).
  void CheckDefinitions() const;

  // "file:line: warning: ...", in the order found, each once.
  const std::vector<std::string>& warnings() const { return warnings_; }

 private:
  void Warn(const std::string& warning) const;
  void WarnTurnsForCycles(const std::string& name, int id, const std::string& attribute, const std::string& si_unit,
                          const std::string& what) const;

  const scripting::IdentifierTable* ids_;
  std::vector<std::optional<Unit>> units_;
  mutable std::vector<std::string> warnings_;  // noted while a const evaluator builds the diagram
};

}  // namespace mechflow::diagrams
