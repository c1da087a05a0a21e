#include "blocks/library/interpolation.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "blocks/library/hysteresis.h"
#include "blocks/outputs/csv.h"
#include "mech/errors.h"

namespace mechflow::blocks {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

}  // namespace

Interpolation ParseInterpolation(const std::string& word) {
  if (word == "step") return Interpolation::kStep;
  if (word == "linear") return Interpolation::kLinear;
  if (word == "cubic") return Interpolation::kCubic;
  throw InputError("'interpolation' must be step, linear or cubic, got '" + word + "'");
}

Extrapolation ParseExtrapolation(const std::string& word) {
  if (word == "hold") return Extrapolation::kHold;
  if (word == "linear") return Extrapolation::kLinear;
  if (word == "error") return Extrapolation::kError;
  throw InputError("'extrapolation' must be hold, linear or error, got '" + word + "'");
}

Axis::Axis(std::vector<double> x, Interpolation interpolation, Extrapolation extrapolation, const std::string& what)
    : x_(std::move(x)), interpolation_(interpolation), extrapolation_(extrapolation), what_(what) {
  if (x_.size() < 2)
    throw InputError(what_ + ": a table needs at least two breakpoints, got " + std::to_string(x_.size()));
  for (std::size_t i = 0; i < x_.size(); ++i) {
    if (!std::isfinite(x_[i])) throw InputError(what_ + ": breakpoint " + CsvNumber(x_[i]) + " is not finite");
    if (i > 0 && !(x_[i] > x_[i - 1]))
      throw InputError(what_ + ": breakpoints must increase strictly, but " + CsvNumber(x_[i]) + " follows " +
                       CsvNumber(x_[i - 1]));
  }
  if (interpolation_ == Interpolation::kStep && extrapolation_ == Extrapolation::kLinear)
    throw InputError(what_ + ": a step table has no slope to extrapolate; use extrapolation=\"hold\" or \"error\"");
  const int n = size();
  const bool kinks = interpolation_ != Interpolation::kCubic;
  const bool smooth_ends = interpolation_ == Interpolation::kLinear && extrapolation_ == Extrapolation::kLinear;
  for (int i = 0; i < n; ++i) {
    const bool end = i == 0 || i == n - 1;
    if (end ? !smooth_ends : kinks) corner_index_.push_back(i);
  }
}

int Axis::Segment(double u) const {
  return static_cast<int>(std::upper_bound(x_.begin(), x_.end(), u) - x_.begin()) - 1;
}

int Axis::Region(double u) const {
  const auto above = std::upper_bound(corner_index_.begin(), corner_index_.end(), u,
                                      [this](double value, int index) { return value < x_[index]; });
  return static_cast<int>(above - corner_index_.begin());
}

double Axis::LowerCorner(int region) const { return region == 0 ? -kInfinity : x_[corner_index_[region - 1]]; }

double Axis::UpperCorner(int region) const {
  return region == num_regions() - 1 ? kInfinity : x_[corner_index_[region]];
}

bool Axis::Forbidden(int region) const {
  if (extrapolation_ != Extrapolation::kError) return false;
  const int last = num_regions() - 1;
  return (region == 0 && corner_index_.front() == 0) || (region == last && corner_index_.back() == size() - 1);
}

int Axis::SegmentIn(double u, int region) const {
  const int first = region == 0 ? -1 : corner_index_[region - 1];
  const int last = region == num_regions() - 1 ? size() - 1 : corner_index_[region] - 1;
  return std::clamp(Segment(u), first, last);
}

void Axis::ThrowBeyond(double u) const {
  throw SimulationError(what_ + ": input " + CsvNumber(u) + " lies outside the table [" + CsvNumber(x_.front()) + ", " +
                        CsvNumber(x_.back()) + "] and extrapolation is \"error\"; extend the table or choose " +
                        "extrapolation=\"hold\" or \"linear\"");
}

void SplineCurvatures(const std::vector<double>& x, const double* y, double* m, double* scratch) {
  const int n = static_cast<int>(x.size());
  auto h = [&](int i) { return x[i + 1] - x[i]; };
  auto d = [&](int i) { return (y[i + 1] - y[i]) / h(i); };
  if (n == 2) {
    m[0] = m[1] = 0.0;
    return;
  }
  if (n == 3) {
    m[0] = m[1] = m[2] = 2.0 * (d(1) - d(0)) / (h(0) + h(1));
    return;
  }
  // Rows i = 1 .. n-2 of h_{i-1} m_{i-1} + 2 (h_{i-1} + h_i) m_i + h_i m_{i+1}
  // = 6 (d_i - d_{i-1}), with m_0 and m_{n-1} eliminated by the not-a-knot
  // conditions (third derivative continuous at x_1 and x_{n-2}); a
  // diagonally dominant tridiagonal system, solved by the Thomas algorithm
  // (scratch: the modified super-diagonal, m: the modified right side).
  const double r0 = h(0) / h(1), r1 = h(n - 2) / h(n - 3);
  for (int i = 1; i <= n - 2; ++i) {
    double sub = i == 1 ? 0.0 : h(i - 1), diag = 2.0 * (h(i - 1) + h(i)), sup = i == n - 2 ? 0.0 : h(i);
    if (i == 1) {  // m_0 = (1 + r0) m_1 - r0 m_2
      diag += h(0) * (1.0 + r0);
      sup -= h(0) * r0;
    }
    if (i == n - 2) {  // m_{n-1} = (1 + r1) m_{n-2} - r1 m_{n-3}
      diag += h(n - 2) * (1.0 + r1);
      sub -= h(n - 2) * r1;
    }
    const double rhs = 6.0 * (d(i) - d(i - 1));
    const double pivot = diag - (i > 1 ? sub * scratch[i - 1] : 0.0);
    scratch[i] = sup / pivot;
    m[i] = (rhs - (i > 1 ? sub * m[i - 1] : 0.0)) / pivot;
  }
  for (int i = n - 3; i >= 1; --i) m[i] -= scratch[i] * m[i + 1];
  m[0] = (1.0 + r0) * m[1] - r0 * m[2];
  m[n - 1] = (1.0 + r1) * m[n - 2] - r1 * m[n - 3];
}

Curve::Curve(const Axis& axis, std::vector<double> y) : y_(std::move(y)) {
  if (static_cast<int>(y_.size()) != axis.size())
    throw InputError(axis.what() + ": " + std::to_string(y_.size()) + " values for " + std::to_string(axis.size()) +
                     " breakpoints");
  for (const double v : y_)
    if (!std::isfinite(v)) throw InputError(axis.what() + ": value " + CsvNumber(v) + " is not finite");
  if (axis.interpolation() == Interpolation::kCubic) {
    m_.resize(y_.size());
    std::vector<double> scratch(y_.size());
    SplineCurvatures(axis.x(), y_.data(), m_.data(), scratch.data());
  }
}

CurvePoint Curve::CurveAt(const Axis& axis, const double* y, const double* m, double u, int segment) {
  const std::vector<double>& x = axis.x();
  const int n = axis.size();
  // segment i's piece at point p (extended past the segment)
  auto piece = [&](int i, double p) -> CurvePoint {
    const double h = x[i + 1] - x[i];
    switch (axis.interpolation()) {
      case Interpolation::kStep:
        return {y[i], 0.0, 0.0};
      case Interpolation::kLinear: {
        const double slope = (y[i + 1] - y[i]) / h;
        return {y[i] + slope * (p - x[i]), slope, 0.0};
      }
      case Interpolation::kCubic: {
        const double a = x[i + 1] - p, b = p - x[i];
        const double value = (m[i] * a * a * a + m[i + 1] * b * b * b) / (6.0 * h) +
                             (y[i] - m[i] * h * h / 6.0) * a / h + (y[i + 1] - m[i + 1] * h * h / 6.0) * b / h;
        const double slope =
            (-m[i] * a * a + m[i + 1] * b * b) / (2.0 * h) + (y[i + 1] - y[i]) / h - (m[i + 1] - m[i]) * h / 6.0;
        return {value, slope, (m[i] * a + m[i + 1] * b) / h};
      }
    }
    return {};
  };
  if (segment >= 0 && segment <= n - 2) return piece(segment, u);
  // beyond an end: the end value, continued along its tangent when linear
  const int end = segment < 0 ? 0 : n - 1;
  if (axis.extrapolation() != Extrapolation::kLinear) return {y[end], 0.0, 0.0};
  const double slope = piece(end == 0 ? 0 : n - 2, x[end]).slope;
  return {y[end] + slope * (u - x[end]), slope, 0.0};
}

namespace {

// True when u lies in `region` widened by the hysteresis band.
bool InsideRegion(const Axis& axis, int region, double u) {
  if (region < 0 || region >= axis.num_regions()) return false;
  const double lower = axis.LowerCorner(region), upper = axis.UpperCorner(region);
  return (region == 0 || u > lower - CornerBand(lower)) &&
         (region == axis.num_regions() - 1 || u < upper + CornerBand(upper));
}

}  // namespace

AxisModes::AxisModes(std::vector<const Axis*> axes) : axes_(std::move(axes)), mode_of_axis_(axes_.size(), -1) {
  for (std::size_t k = 0; k < axes_.size(); ++k)
    if (axes_[k]->has_corners()) {
      mode_of_axis_[k] = static_cast<int>(moded_.size());
      moded_.push_back(static_cast<int>(k));
    }
}

void AxisModes::Initialize(std::span<double> modes) const {
  // inputs are not valid yet: Settle classifies once they are
  for (int i = 0; i < num_modes(); ++i) modes[i] = kUnclassified;
}

void AxisModes::Crossings(std::span<const double> u, std::span<const double> modes, std::span<double> g) const {
  for (int i = 0; i < num_modes(); ++i) {
    const Axis& axis = *axes_[moded_[i]];
    const double value = u[moded_[i]];
    double& lower = g[2 * i];
    double& upper = g[2 * i + 1];
    lower = 1.0;
    upper = -1.0;
    if (modes[i] == kUnclassified) continue;
    const int r = static_cast<int>(modes[i]);
    const double below = axis.LowerCorner(r), above = axis.UpperCorner(r);
    if (r > 0) lower = value - (below - CornerBand(below));
    if (r < axis.num_regions() - 1) upper = value - (above + CornerBand(above));
  }
}

void AxisModes::Cross(int i, std::span<const double> u, std::span<double> modes) const {
  const int k = i / 2;
  const Axis& axis = *axes_[moded_[k]];
  const int next = static_cast<int>(modes[k]) + (CrossingRises(i) ? 1 : -1);
  if (modes[k] == kUnclassified || next < 0 || next >= axis.num_regions()) return;
  if (axis.Forbidden(next)) axis.ThrowBeyond(u[moded_[k]]);
  modes[k] = next;
}

bool AxisModes::Settle(std::span<const double> u, std::span<double> modes) const {
  for (std::size_t k = 0; k < axes_.size(); ++k) {
    const Axis& axis = *axes_[k];
    if ((u[k] < axis.x().front() || u[k] > axis.x().back()) && axis.extrapolation() == Extrapolation::kError)
      axis.ThrowBeyond(u[k]);
  }
  bool changed = false;
  for (int i = 0; i < num_modes(); ++i) {
    const Axis& axis = *axes_[moded_[i]];
    const double value = u[moded_[i]];
    double mode = modes[i];
    if (!InsideRegion(axis, static_cast<int>(mode), value)) {
      mode = axis.Region(value);
      if (axis.Forbidden(static_cast<int>(mode))) mode -= 1;  // exactly on the last breakpoint
    }
    changed |= mode != modes[i];
    modes[i] = mode;
  }
  return changed;
}

int AxisModes::Segment(int k, double u, std::span<const double> modes) const {
  const Axis& axis = *axes_[k];
  const int i = mode_of_axis_[k];
  int segment = i < 0 || modes[i] == kUnclassified ? axis.Segment(u) : axis.SegmentIn(u, static_cast<int>(modes[i]));
  // a trial step a hair outside a table that must not be left: its end piece, extended
  if (axis.extrapolation() == Extrapolation::kError) segment = std::clamp(segment, 0, axis.size() - 2);
  return segment;
}

}  // namespace mechflow::blocks
