#pragma once
// --constraint A<=B (or >=) between two free parameters: mu_k<=mu_s. A point
// that breaks one is not run: its residuals are those of a failed run (large,
// analysis/fit/residuals.h), so both optimisers step back from it, as from a
// value the model refuses (a contact's mu_static below its mu).

#include <string>
#include <vector>

#include "analysis/fit/parameters.h"

namespace mechflow::analysis::fit {

struct Constraint {
  std::string text;      // as given
  int lower = 0, upper = 0;  // parameter indices: value[lower] <= value[upper]
};

// Throws InputError: not of the form A<=B or A>=B, or a name that is not a
// free parameter.
Constraint ParseConstraint(const std::string& text, const std::vector<FreeParameter>& parameters);

// "" when `values` keep every constraint, else what breaks the first that fails.
std::string Broken(const std::vector<Constraint>& constraints, const std::vector<FreeParameter>& parameters,
                   const std::vector<double>& values);

}  // namespace mechflow::analysis::fit
