#include "blocks/solver/coloured_jacobian.h"

#include <algorithm>
#include <limits>

namespace mechflow::blocks {

void DifferenceIncrements(int n, const double* x, const double* f, const double* weights, double step,
                          double* increments) {
  const double u = std::numeric_limits<double>::epsilon();
  double sum = 0.0;  // weighted RMS norm of f
  for (int i = 0; i < n; ++i) sum += (f[i] * weights[i]) * (f[i] * weights[i]);
  const double norm = std::sqrt(sum / n);
  const double min_increment = norm != 0.0 ? 1000.0 * std::abs(step) * u * n * norm : 1.0;
  const double root_u = std::sqrt(u);
  for (int j = 0; j < n; ++j) increments[j] = std::max(root_u * std::abs(x[j]), min_increment / weights[j]);
}

ColouredJacobian::ColouredJacobian(SparsityPattern pattern)
    : pattern_(std::move(pattern)), values_(pattern_.nonzeros(), 0.0), x_(pattern_.n, 0.0), f_(pattern_.n, 0.0) {
  colour_ = ColourColumns(pattern_, &num_colours_);
  colour_start_.assign(num_colours_ + 1, 0);
  for (const int c : colour_) ++colour_start_[c + 1];
  for (int c = 0; c < num_colours_; ++c) colour_start_[c + 1] += colour_start_[c];
  colour_columns_.resize(pattern_.n);
  std::vector<int> next(colour_start_.begin(), colour_start_.end() - 1);
  for (int j = 0; j < pattern_.n; ++j) colour_columns_[next[colour_[j]]++] = j;
}

}  // namespace mechflow::blocks
