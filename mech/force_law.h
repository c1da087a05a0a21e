#pragma once
// Scalar force laws F(x, v, t) shared by bipolar forces (x: length, v: its
// rate) and joint forces (x: coordinate, v: its velocity), ELEMENTS.md 3.3-3.5.
//
//   Linear:     F = -c (x - x0) - d v + F0
//   Points:     F = table(x) - d v; table piecewise linear or a natural cubic
//               spline through (x_i, F_i), x strictly increasing; beyond the
//               ends extended linearly along the end slopes (default) or
//               clamped to the end values
//   Expression: F = f(x, v, t, inputs...), a ScalarFunction supplied by the
//               loader (a compiled Lua expression)
//
// Every parameter is a mech::Parameter (constant or a function of the
// mechanism's inputs).
//
// Linear's x0 is always a value here: "unset" in a model means the initial
// length (bipolar: BipolarLength in the initial configuration) or the
// initial coordinate (joint force); the loader resolves it before it builds
// the law, so the element needs no run state for it.
//
// Laws are immutable after construction and Force() keeps its scratch on the
// stack, so one law may be evaluated from several threads; the ScalarFunction
// of an Expression law decides that for itself (compiled Lua: one mechanism
// per thread).

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "mech/force_element.h"

namespace mechflow::mech {

class ForceLaw {
 public:
  virtual ~ForceLaw() = default;
  virtual double Force(double x, double v, const ElementContext& ctx) const = 0;
  virtual bool depends_on_inputs() const = 0;
  // dF/dx and dF/dv at (x, v), when the law knows them (has_derivatives).
  virtual bool has_derivatives() const { return false; }
  virtual void Derivatives(double /*x*/, double /*v*/, const ElementContext&, double* /*force_x*/,
                           double* /*force_v*/) const {}
  // A potential U(x) with F = -dU/dx - (the damping part), when the law has
  // one that does not change in time (the stored-energy sensor reads it).
  virtual bool has_energy() const { return false; }
  virtual double Energy(double /*x*/, const ElementContext&) const { return 0.0; }
};

class LinearLaw final : public ForceLaw {
 public:
  LinearLaw(Parameter c, Parameter x0, Parameter d, Parameter f0) : c_(c), x0_(x0), d_(d), f0_(f0) {}
  double Force(double x, double v, const ElementContext& ctx) const override {
    return -c_.Get(ctx) * (x - x0_.Get(ctx)) - d_.Get(ctx) * v + f0_.Get(ctx);
  }
  bool depends_on_inputs() const override {
    return c_.uses_inputs || x0_.uses_inputs || d_.uses_inputs || f0_.uses_inputs;
  }
  bool has_derivatives() const override { return true; }
  void Derivatives(double, double, const ElementContext& ctx, double* force_x, double* force_v) const override {
    *force_x = -c_.Get(ctx);
    *force_v = -d_.Get(ctx);
  }
  // U = c/2 (x - x0)^2 - F0 (x - x0), when c, x0 and F0 are constants.
  bool has_energy() const override { return c_.is_constant() && x0_.is_constant() && f0_.is_constant(); }
  double Energy(double x, const ElementContext&) const override {
    const double s = x - x0_.value;
    return 0.5 * c_.value * s * s - f0_.value * s;
  }

 private:
  Parameter c_, x0_, d_, f0_;
};

class PointsLaw final : public ForceLaw {
 public:
  enum class Interpolation { kLinear, kSpline };
  enum class Extrapolation { kLinear, kClamp };
  // Throws InputError (starting with `origin`) for fewer than two points, x
  // and F of different lengths, a non-finite value, or x not strictly
  // increasing. Beyond the table: kLinear continues the end segment (for a
  // spline: its end tangent), so F and its slope stay continuous; kClamp
  // holds the end value.
  PointsLaw(std::vector<double> x, std::vector<double> f, Interpolation interpolation, Extrapolation extrapolation,
            Parameter d, const std::string& origin);
  double Force(double x, double v, const ElementContext& ctx) const override;
  bool depends_on_inputs() const override { return d_.uses_inputs; }
  bool has_derivatives() const override { return true; }
  void Derivatives(double x, double, const ElementContext& ctx, double* force_x, double* force_v) const override {
    *force_x = Slope(x);
    *force_v = -d_.Get(ctx);
  }
  double Table(double x) const;
  double Slope(double x) const;  // dTable/dx (at a knot of a linear table: the segment to its right)

 private:
  double EndSlope(std::size_t i0) const;  // of the spline or segment at an end (i0 = 0 or n - 2)
  std::vector<double> x_, f_, second_;  // second_: spline second derivatives
  Interpolation interpolation_;
  Extrapolation extrapolation_;
  Parameter d_;
};

class ExpressionLaw final : public ForceLaw {
 public:
  static constexpr int kMaxInputs = 32;
  // `function` takes [x, v, t, inputs...]: x and v, then ctx.parameter_args
  // ([t, inputs...]) copied into a stack buffer (no allocation). A mechanism
  // with more than kMaxInputs inputs makes Force() throw SimulationError.
  // `uses_inputs`: whether the expression reads any input.
  ExpressionLaw(std::shared_ptr<const ScalarFunction> function, bool uses_inputs);
  double Force(double x, double v, const ElementContext& ctx) const override;
  bool depends_on_inputs() const override { return uses_inputs_; }

 private:
  std::shared_ptr<const ScalarFunction> function_;
  bool uses_inputs_;
};

}  // namespace mechflow::mech
