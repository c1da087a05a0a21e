#include "blocks/solver/step_polynomial.h"

#include <algorithm>

namespace mechflow::blocks {

using sundials::Check;

StepPolynomial::StepPolynomial(sunindextype n, const sundials::Context& ctx) : n_(static_cast<std::size_t>(n)) {
  for (int k = 0; k <= kMaxOrder; ++k) taylor_.push_back(std::make_unique<sundials::Vector>(n, ctx));
}

void StepPolynomial::At(void* mem, double t, double* out) {
  const std::size_t n = n_;
  if (order_ < 0) {
    // the step's polynomial about its end tn: y(t) = sum_k y^(k)(tn) (t - tn)^k / k!
    Check(CVodeGetLastOrder(mem, &order_), "CVodeGetLastOrder");
    Check(CVodeGetCurrentTime(mem, &tn_), "CVodeGetCurrentTime");
    double factorial = 1.0;
    for (int k = 0; k <= order_; ++k) {
      Check(CVodeGetDky(mem, tn_, k, taylor_[k]->get()), "CVodeGetDky");
      factorial *= std::max(k, 1);
      double* a = taylor_[k]->data();
      for (std::size_t i = 0; k > 1 && i < n; ++i) a[i] /= factorial;
    }
  }
  const double dt = t - tn_;
  const double* a = taylor_[order_]->data();
  std::copy(a, a + n, out);
  for (int k = order_ - 1; k >= 0; --k) {
    a = taylor_[k]->data();
    for (std::size_t i = 0; i < n; ++i) out[i] = out[i] * dt + a[i];
  }
}

}  // namespace mechflow::blocks
