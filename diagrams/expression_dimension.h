#pragma once
// The dimension of an expression (a Lua expression of identifiers, as
// identifier definitions and attributes are written), as far as the units of
// the identifiers it names tell it: `4*pi^2*f^2*m` with f in Hz and m in kg
// is a stiffness. Numbers are dimensionless factors, and in a sum they take
// the dimension of what they are added to (numbers in expressions are SI
// values). Whatever this small reader does not follow (comparisons, and/or,
// strings, fields, a name without a unit, an unknown function) leaves the
// dimension unknown: it never rejects an expression, Lua does that.

#include <functional>
#include <optional>
#include <string>

#include "diagrams/units.h"

namespace mechflow::diagrams {

struct ExpressionDimension {
  bool known = false;
  Dimension dimension;
  // made of numbers only ("1e-5", "2*3"): an SI value of any dimension
  bool plain_number = false;
  // not empty: the expression adds quantities of different dimensions
  // ("adds a length (m) and a mass (kg)")
  std::string conflict;
};

// `dimension_of(name)`: the dimension of a name the expression uses (an
// identifier with a unit), or nullopt when it is not known.
ExpressionDimension InferDimension(const std::string& text,
                                   const std::function<std::optional<Dimension>(const std::string&)>& dimension_of);

}  // namespace mechflow::diagrams
