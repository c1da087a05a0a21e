#pragma once
// Functions of time that the mechanics evaluates while it runs.
//
// mech/ knows nothing of Lua or of the expression syntax; the layer that reads
// a model (scripting/, diagrams/) supplies these through the two interfaces.

#include <memory>
#include <span>

namespace mechflow::mech {

// A value with its first and second time derivatives, exact (not differenced).
struct Jet {
  double value = 0.0;
  double rate = 0.0;          // d/dt
  double acceleration = 0.0;  // d2/dt2
};

// s(t) of a prescribed elementary transformation (tt, rt) or coordinate.
class TimeFunction {
 public:
  virtual ~TimeFunction() = default;
  // Must not allocate; throws SimulationError for a non-finite result.
  virtual Jet Evaluate(double t) const = 0;
};

// f(args) of a force law: args are whatever the element documents (for the
// scalar laws: x, v, t, then the model's input values).
class ScalarFunction {
 public:
  virtual ~ScalarFunction() = default;
  // Must not allocate; throws SimulationError for a non-finite result.
  virtual double Evaluate(std::span<const double> args) const = 0;
};

// A time function that is a constant (used by tests and by locked DOFs).
class ConstantTimeFunction final : public TimeFunction {
 public:
  explicit ConstantTimeFunction(double value) : value_(value) {}
  Jet Evaluate(double) const override { return {value_, 0.0, 0.0}; }

 private:
  double value_;
};

}  // namespace mechflow::mech
