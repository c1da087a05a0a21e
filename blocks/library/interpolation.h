#pragma once
// Interpolation in tables: one axis of breakpoints, the curves over it, and
// the frozen-region bookkeeping that turns the breakpoints where a curve is
// not smooth into events.
//
// Along an axis x_0 < ... < x_{n-1}, a curve through values y_i is
//   step    y = y_i on [x_i, x_{i+1})                 (jumps at every x_i)
//   linear  straight lines between the points          (kinks at every x_i)
//   cubic   the not-a-knot cubic spline (as MATLAB's spline): continuous up
//           to the second derivative, so no event inside the table; three
//           points give the parabola, two the line
// and beyond x_0 and x_{n-1}
//   hold    the end value (y' = 0)
//   linear  the end's tangent (step tables cannot: refused)
//   error   refused: a run that reaches the end fails there, naming it.
//
// Segments: -1 below x_0, i on [x_i, x_{i+1}), n-1 at and above x_{n-1}.
//
// Corners are the breakpoints where the curve or one of its first two
// derivatives jumps: every x_i for step and linear, and the ends unless the
// curve continues as it was (linear interpolation, linear extrapolation).
// Corners split the axis into regions. A block keeps the region of each
// input as a mode and, inside a solver step, evaluates only that region's
// pieces, extended past its ends when a trial step overshoots; two
// crossings (the input minus the region's lower and upper corner) move it
// to the next region at the located instant. So the right-hand side is
// smooth inside every step, as for blocks/library/piecewise_linear.h.
// Smooth curves have no corners and need no modes.
//
// Lookups are a binary search (std::upper_bound); nothing allocates after
// construction.

#include <span>
#include <string>
#include <vector>

namespace mechflow::blocks {

enum class Interpolation { kStep, kLinear, kCubic };
enum class Extrapolation { kHold, kLinear, kError };

// From the XML words (step, linear, cubic; hold, linear, error); InputError
// listing the choices otherwise.
Interpolation ParseInterpolation(const std::string& word);
Extrapolation ParseExtrapolation(const std::string& word);

// A value of a curve with its first two derivatives along the axis.
struct CurvePoint {
  double value = 0.0;
  double slope = 0.0;      // dy/dx
  double curvature = 0.0;  // d2y/dx2
};

class Axis {
 public:
  // `x` strictly increasing and finite, at least two points (InputError
  // naming `what` otherwise); step with linear extrapolation is refused.
  Axis(std::vector<double> x, Interpolation interpolation, Extrapolation extrapolation, const std::string& what);

  int size() const { return static_cast<int>(x_.size()); }
  const std::vector<double>& x() const { return x_; }
  Interpolation interpolation() const { return interpolation_; }
  Extrapolation extrapolation() const { return extrapolation_; }
  const std::string& what() const { return what_; }

  // The segment holding u (see above).
  int Segment(double u) const;

  // --- regions between corners (events) ---
  bool has_corners() const { return !corner_index_.empty(); }
  int num_regions() const { return static_cast<int>(corner_index_.size()) + 1; }
  // The region holding u (a corner belongs to the region above it).
  int Region(double u) const;
  // Corner below / above region r (-inf / +inf at the outer regions).
  double LowerCorner(int region) const;
  double UpperCorner(int region) const;
  // True for a region outside the table when extrapolation is an error.
  bool Forbidden(int region) const;
  // The segment to evaluate u on while frozen in `region`: the segment
  // holding u, limited to the region's own.
  int SegmentIn(double u, int region) const;
  // SimulationError: input u has left the table (extrapolation="error").
  [[noreturn]] void ThrowBeyond(double u) const;

 private:
  std::vector<double> x_;
  Interpolation interpolation_;
  Extrapolation extrapolation_;
  std::string what_;
  std::vector<int> corner_index_;  // breakpoint index of each corner, increasing
};

// Values over an axis, interpolated as the axis says.
class Curve {
 public:
  Curve() = default;
  Curve(const Axis& axis, std::vector<double> y);

  // The piece of `segment` at u (extended beyond the segment when u lies
  // outside it).
  CurvePoint At(const Axis& axis, double u, int segment) const {
    return CurveAt(axis, y_.data(), m_.empty() ? nullptr : m_.data(), u, segment);
  }

  // The same for values y and spline curvatures m (cubic; else unused) kept
  // elsewhere (curves built at run time).
  static CurvePoint CurveAt(const Axis& axis, const double* y, const double* m, double u, int segment);

 private:
  std::vector<double> y_;
  std::vector<double> m_;  // cubic: second derivatives at the breakpoints
};

// The not-a-knot spline's second derivatives m (size n) at breakpoints x of
// values y; `scratch` of size n. Allocation-free, for curves built at run
// time (the second axis of a 2-D cubic table).
void SplineCurvatures(const std::vector<double>& x, const double* y, double* m, double* scratch);

// The frozen regions of a block's inputs, one input per axis (axes without
// corners take no part): one mode each, the region, and two crossings each
// (the input minus the region's lower corner less the band, an event when
// falling; minus its upper corner plus the band, an event when rising).
class AxisModes {
 public:
  static constexpr double kUnclassified = -1.0;  // before the first Settle

  explicit AxisModes(std::vector<const Axis*> axes);
  int num_modes() const { return static_cast<int>(moded_.size()); }
  int num_crossings() const { return 2 * num_modes(); }
  // Crossing i's direction: even ones fall, odd ones rise.
  static bool CrossingRises(int i) { return i % 2 == 1; }

  // inputs u[k] along axis k; modes and crossings as declared above
  void Initialize(std::span<double> modes) const;
  void Crossings(std::span<const double> u, std::span<const double> modes, std::span<double> g) const;
  // For the event log: "u rises past a breakpoint" (`inputs`: port names).
  std::string CrossingName(int i, const std::vector<std::string>& inputs) const {
    return inputs.at(moded_.at(i / 2)) + (CrossingRises(i) ? " rises" : " falls") + " past a breakpoint";
  }
  // Crossing i fired: move to the next region (SimulationError into a
  // forbidden one).
  void Cross(int i, std::span<const double> u, std::span<double> modes) const;
  // After an event or at the start: keep each region while its input is
  // inside (widened by the band), else classify; SimulationError for an input
  // beyond a table that must not be left. True when a mode changed.
  bool Settle(std::span<const double> u, std::span<double> modes) const;
  // The segment to evaluate input k on.
  int Segment(int k, double u, std::span<const double> modes) const;

 private:
  std::vector<const Axis*> axes_;
  std::vector<int> mode_of_axis_;  // -1: no corners
  std::vector<int> moded_;         // the axes with corners
};

}  // namespace mechflow::blocks
