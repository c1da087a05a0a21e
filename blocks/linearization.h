#pragma once
// Linear analysis of a diagram (ELEMENTS.md 8): the Jacobian of x' = f(x) at
// a state, the static equilibrium, and the eigen-analysis that turns the
// Jacobian into natural frequencies, damping ratios and mode shapes.
//
// Generic over any diagram: it works on the continuous state vector, so a
// mechanism's (q, v) and any block states are analysed together. Inputs are
// held at what the diagram computes at the analysed state and time; modes of
// nonsmooth blocks stay as initialised.

#include <complex>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "blocks/diagram.h"

namespace mechflow::blocks {

// Sets up a Context for the diagram at t with the initial states; `x` gets
// the initial continuous state.
void PrepareContext(const Diagram& diagram, double t, Context* ctx, std::vector<double>* x);

// x' at x (outputs evaluated first).
void StateDerivative(const Diagram& diagram, Context* ctx, std::vector<double>* x, std::vector<double>* xdot);

// A = d(x')/dx by central differences, step sqrt(eps)-scaled per state.
Eigen::MatrixXd StateJacobian(const Diagram& diagram, Context* ctx, const std::vector<double>& x);

// Newton on x'(x) = 0 from `x` (least-norm steps, so neutral directions such
// as a free coordinate are left where they are); throws SimulationError with
// the residual when it does not converge within `max_iterations`.
void FindEquilibrium(const Diagram& diagram, Context* ctx, std::vector<double>* x, double tolerance = 1e-10,
                     int max_iterations = 50);

struct Mode {
  std::complex<double> eigenvalue;     // [rad/s]
  double frequency_hz = 0.0;           // damped: |Im| / 2 pi
  double natural_frequency_hz = 0.0;   // undamped: |lambda| / 2 pi
  double damping_ratio = 0.0;          // -Re / |lambda|; 1 for a real decaying eigenvalue
  std::vector<double> shape;           // per state, largest component 1
};

// One mode per complex-conjugate pair and per real eigenvalue, sorted by
// natural frequency. Shapes are scaled so that the largest of the states
// marked in `normalise_on` (e.g. the coordinates, not their rates) is 1; all
// states when it is empty.
std::vector<Mode> ModalAnalysis(const Eigen::MatrixXd& A, const std::vector<bool>& normalise_on = {});

// "block.state" names of the continuous states, in state order.
std::vector<std::string> StateNames(const Diagram& diagram);

}  // namespace mechflow::blocks
