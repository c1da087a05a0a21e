#pragma once
// ColouredJacobian: df/dx by difference quotients, one right-hand side per
// colour of the structural pattern (Curtis, Powell and Reid, 1974).
//
// Columns that share no row are perturbed together: each row of the
// perturbed f then changes because of exactly one of them, so
//   J(i, j) = (f_i(x + sum_{j in colour} h_j e_j) - f_i(x)) / h_j
// for every nonzero (i, j) of column j. With k colours a fill costs k
// right-hand sides instead of n. The pattern and colouring are computed once
// (at construction); Fill allocates nothing.
//
// Increments follow CVODE's dense difference-quotient rule so both Jacobians
// can be compared entry by entry (DifferenceIncrements).

#include <cmath>
#include <vector>

#include "blocks/solver/sparsity.h"

namespace mechflow::blocks {

// The increments CVODE's dense difference-quotient Jacobian uses (SUNDIALS
// 6.x, cvLsDenseDQJac): h_j = max(sqrt(u) |x_j|, m / w_j) with u the unit
// roundoff, w the error weights and m = 1000 |step| u n ||f||_wrms (m = 1 when
// f is zero). `step` is the integrator's current step [s].
void DifferenceIncrements(int n, const double* x, const double* f, const double* weights, double step,
                          double* increments);

class ColouredJacobian {
 public:
  explicit ColouredJacobian(SparsityPattern pattern);

  const SparsityPattern& pattern() const { return pattern_; }
  int num_colours() const { return num_colours_; }
  const std::vector<int>& colours() const { return colour_; }
  // J's nonzeros in the pattern's order (compressed columns), after Fill.
  const std::vector<double>& values() const { return values_; }

  // Fills J at x, where f0 = f(x). `rhs(x, f)` evaluates f at x into f and
  // returns 0, or a nonzero value that Fill returns at once (J then invalid).
  template <class Rhs>
  int Fill(const double* x, const double* f0, const double* increments, Rhs&& rhs);

 private:
  SparsityPattern pattern_;
  std::vector<int> colour_;
  int num_colours_ = 0;
  std::vector<int> colour_start_, colour_columns_;  // columns grouped by colour
  std::vector<double> values_;
  std::vector<double> x_, f_;  // perturbed state and its f
};

template <class Rhs>
int ColouredJacobian::Fill(const double* x, const double* f0, const double* increments, Rhs&& rhs) {
  const int n = pattern_.n;
  for (int i = 0; i < n; ++i) x_[i] = x[i];
  for (int c = 0; c < num_colours_; ++c) {
    for (int k = colour_start_[c]; k < colour_start_[c + 1]; ++k) {
      const int j = colour_columns_[k];
      x_[j] = x[j] + increments[j];
    }
    if (const int flag = rhs(x_.data(), f_.data()); flag != 0) return flag;
    for (int k = colour_start_[c]; k < colour_start_[c + 1]; ++k) {
      const int j = colour_columns_[k];
      // as CVODE's dense quotient: the nominal increment, its reciprocal
      const double inverse = 1.0 / increments[j];
      for (int m = pattern_.column_start[j]; m < pattern_.column_start[j + 1]; ++m) {
        const int i = pattern_.rows[m];
        values_[m] = inverse * f_[i] - inverse * f0[i];
      }
      x_[j] = x[j];
    }
  }
  return 0;
}

}  // namespace mechflow::blocks
