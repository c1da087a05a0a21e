#include "mech/force_law.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "mech/errors.h"

namespace mechflow::mech {

PointsLaw::PointsLaw(std::vector<double> x, std::vector<double> f, Interpolation interpolation,
                     Extrapolation extrapolation, Parameter d, const std::string& origin)
    : x_(std::move(x)), f_(std::move(f)), interpolation_(interpolation), extrapolation_(extrapolation), d_(d) {
  const std::string where = origin.empty() ? "" : origin + ": ";
  if (x_.size() != f_.size())
    throw InputError(where + "a points table needs as many F values as x values (" + std::to_string(x_.size()) +
                     " x, " + std::to_string(f_.size()) + " F)");
  if (x_.size() < 2) throw InputError(where + "a points table needs at least two (x, F) pairs");
  for (std::size_t i = 0; i < x_.size(); ++i)
    if (!std::isfinite(x_[i]) || !std::isfinite(f_[i]))
      throw InputError(where + "points table: point " + std::to_string(i + 1) + " is not finite");
  for (std::size_t i = 1; i < x_.size(); ++i)
    if (!(x_[i] > x_[i - 1]))
      throw InputError(where + "points table: x must increase strictly (point " + std::to_string(i + 1) + ")");
  // Natural cubic spline: tridiagonal system for the second derivatives.
  const std::size_t n = x_.size();
  second_.assign(n, 0.0);
  if (interpolation_ == Interpolation::kSpline && n > 2) {
    std::vector<double> diag(n, 1.0), rhs(n, 0.0), upper(n, 0.0), lower(n, 0.0);
    for (std::size_t i = 1; i + 1 < n; ++i) {
      const double h0 = x_[i] - x_[i - 1], h1 = x_[i + 1] - x_[i];
      lower[i] = h0 / 6;
      diag[i] = (h0 + h1) / 3;
      upper[i] = h1 / 6;
      rhs[i] = (f_[i + 1] - f_[i]) / h1 - (f_[i] - f_[i - 1]) / h0;
    }
    for (std::size_t i = 1; i < n; ++i) {  // Thomas algorithm
      const double m = lower[i] / diag[i - 1];
      diag[i] -= m * upper[i - 1];
      rhs[i] -= m * rhs[i - 1];
    }
    second_[n - 1] = rhs[n - 1] / diag[n - 1];
    for (std::size_t i = n - 1; i-- > 0;) second_[i] = (rhs[i] - upper[i] * second_[i + 1]) / diag[i];
  }
}

double PointsLaw::EndSlope(std::size_t i0) const {
  const std::size_t n = x_.size();
  const double h = x_[i0 + 1] - x_[i0];
  const double secant = (f_[i0 + 1] - f_[i0]) / h;
  if (interpolation_ == Interpolation::kLinear) return secant;
  return i0 == 0 ? secant - h * (2 * second_[0] + second_[1]) / 6
                 : secant + h * (second_[n - 2] + 2 * second_[n - 1]) / 6;
}

double PointsLaw::Table(double x) const {
  const std::size_t n = x_.size();
  if (x <= x_.front()) {
    return extrapolation_ == Extrapolation::kClamp ? f_.front() : f_.front() + EndSlope(0) * (x - x_.front());
  }
  if (x >= x_.back()) {
    return extrapolation_ == Extrapolation::kClamp ? f_.back() : f_.back() + EndSlope(n - 2) * (x - x_.back());
  }
  const std::size_t i = static_cast<std::size_t>(std::upper_bound(x_.begin(), x_.end(), x) - x_.begin()) - 1;
  const double h = x_[i + 1] - x_[i];
  const double a = (x_[i + 1] - x) / h, b = (x - x_[i]) / h;
  double value = a * f_[i] + b * f_[i + 1];
  if (interpolation_ == Interpolation::kSpline)
    value += ((a * a * a - a) * second_[i] + (b * b * b - b) * second_[i + 1]) * h * h / 6;
  return value;
}

double PointsLaw::Slope(double x) const {
  const std::size_t n = x_.size();
  if (x < x_.front()) return extrapolation_ == Extrapolation::kClamp ? 0.0 : EndSlope(0);
  if (x >= x_.back()) return extrapolation_ == Extrapolation::kClamp ? 0.0 : EndSlope(n - 2);
  const std::size_t i = static_cast<std::size_t>(std::upper_bound(x_.begin(), x_.end(), x) - x_.begin()) - 1;
  const double h = x_[i + 1] - x_[i];
  double slope = (f_[i + 1] - f_[i]) / h;
  if (interpolation_ == Interpolation::kSpline) {
    const double a = (x_[i + 1] - x) / h, b = (x - x_[i]) / h;
    slope += ((1 - 3 * a * a) * second_[i] + (3 * b * b - 1) * second_[i + 1]) * h / 6;
  }
  return slope;
}

double PointsLaw::Force(double x, double v, const ElementContext& ctx) const { return Table(x) - d_.Get(ctx) * v; }

ExpressionLaw::ExpressionLaw(std::shared_ptr<const ScalarFunction> function, bool uses_inputs)
    : function_(std::move(function)), uses_inputs_(uses_inputs) {
  if (!function_) throw std::invalid_argument("ExpressionLaw: no function");
}

double ExpressionLaw::Force(double x, double v, const ElementContext& ctx) const {
  std::array<double, 3 + kMaxInputs> args;
  args[0] = x;
  args[1] = v;
  const std::size_t extra = ctx.parameter_args.size();  // [t, inputs...]
  if (extra > args.size() - 2)
    throw SimulationError("expression force law: the mechanism has " + std::to_string(extra - 1) +
                          " inputs; an expression law takes at most " + std::to_string(kMaxInputs));
  if (extra == 0) {  // a context without parameter arguments (no mechanism): t alone
    args[2] = ctx.t;
    return function_->Evaluate(std::span<const double>(args.data(), 3));
  }
  for (std::size_t i = 0; i < extra; ++i) args[2 + i] = ctx.parameter_args[i];
  return function_->Evaluate(std::span<const double>(args.data(), 2 + extra));
}

}  // namespace mechflow::mech
