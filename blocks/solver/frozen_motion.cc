#include "blocks/solver/frozen_motion.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "blocks/solver/cvode_run.h"
#include "mech/errors.h"

namespace mechflow::blocks {


int FrozenState(std::span<const double> before, std::span<const double> after, std::span<const double> slope,
                double dt, double rtol, double atol) {
  if (!std::equal(before.begin(), before.end(), after.begin(), after.end())) return -1;
  for (std::size_t i = 0; i < after.size(); ++i)
    if (std::abs(slope[i]) * dt > 1e-3 * (rtol * std::abs(after[i]) + atol)) return static_cast<int>(i);
  return -1;
}

FrozenMotionGuard::FrozenMotionGuard(int states, double rtol, double atol)
    : rtol_(rtol), atol_(atol), y_(states, 0.0), before_(states, 0.0), slope_(states, 0.0) {}

void FrozenMotionGuard::Check(const CvodeRun& cvode) {
  if (y_.empty()) return;  // no states, nothing can freeze
  void* mem = cvode.mem();
  double tn = 0.0;
  N_Vector yn = nullptr;
  sundials::Check(CVodeGetCurrentTime(mem, &tn), "CVodeGetCurrentTime");
  sundials::Check(CVodeGetCurrentState(mem, &yn), "CVodeGetCurrentState");
  const double* y = N_VGetArrayPointer(yn);
  const std::size_t n = y_.size();
  const bool advanced = valid_ && tn > tn_;
  const double tn_before = tn_;
  std::copy(y_.begin(), y_.end(), before_.begin());
  valid_ = true;
  tn_ = tn;
  std::copy(y, y + n, y_.begin());
  if (!advanced || !std::equal(y, y + n, before_.begin())) return;
  // the solver's own derivative there
  N_Vector slope = sundials::WrapArray(static_cast<sunindextype>(n), slope_.data(), cvode.sundials_context());
  const int flag = CVodeGetDky(mem, tn, 1, slope);
  N_VDestroy(slope);
  sundials::Check(flag, "CVodeGetDky");
  const int i = FrozenState(before_, y_, slope_, tn - tn_before, rtol_, atol_);
  if (i < 0) return;
  std::ostringstream out;
  out << "the integrator's state stopped changing from t = " << tn_before << " to " << tn
      << " s while its derivative is not zero (state " << i << ": x' = " << slope_[i]
      << "): refusing to write rows of frozen motion";
  throw SimulationError(out.str());
}

}  // namespace mechflow::blocks
