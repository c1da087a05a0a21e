#pragma once
// The last step's polynomial as Taylor coefficients y^(k)(tn)/k! (k = 0 ..
// order), from CVodeGetDky once per step, for a step with several rows:
// instead of a CVodeGetDky per row (Debian's unoptimised SUNDIALS build: 7 %
// of the P1 benchmark).

#include <cstddef>
#include <memory>
#include <vector>

#include "blocks/solver/sundials.h"

namespace mechflow::blocks {

class StepPolynomial {
 public:
  static constexpr int kMaxOrder = 5;  // BDF's

  StepPolynomial(sunindextype n, const sundials::Context& ctx);

  // A new step: its polynomial is not known yet.
  void Forget() { order_ = -1; }
  bool known() const { return order_ >= 0; }
  // The state at t inside CVODE's last step into out (n values); finds the
  // coefficients on first use in the step.
  void At(void* cvode_mem, double t, double* out);

 private:
  const std::size_t n_;  // states
  std::vector<std::unique_ptr<sundials::Vector>> taylor_;
  int order_ = -1;  // -1: not found for this step
  double tn_ = 0.0;
};

}  // namespace mechflow::blocks
