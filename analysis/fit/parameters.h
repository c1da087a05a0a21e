#pragma once
// The free parameters of a fit: identifiers of the diagram defined by a
// number, each between bounds, fitted on a linear or a log scale.
//
// The optimisers see every parameter as u in [0, 1] across its bounds
// (linearly, or in log of the value for a log scale): parameters of very
// different sizes (a friction coefficient, a contact stiffness of 1e6 N/m)
// get comparable steps, bounds are the box [0, 1]^n, and a forward
// difference step is a fixed fraction of each range.

#include <string>
#include <vector>

namespace mechflow::analysis::fit {

struct FreeParameter {
  std::string name;  // as given; the identifier (any case)
  double lower = 0.0, upper = 0.0;
  bool log = false;  // fitted in log space (lower > 0)
  double start = 0.0;  // the model's value (moved inside the bounds when on one)

  double ToUnit(double value) const;  // value -> u
  double FromUnit(double u) const;    // u -> value
  double Slope(double u) const;       // d value / d u
};

// "NAME=LOWER:UPPER" or "NAME=LOWER:UPPER:log" (--free). Throws InputError
// saying what is wrong (bounds missing, not numbers, lower >= upper, a log
// scale with lower <= 0).
FreeParameter ParseFree(const std::string& text);

// The physical values of the point `u`.
std::vector<double> FromUnit(const std::vector<FreeParameter>& parameters, const std::vector<double>& u);

}  // namespace mechflow::analysis::fit
