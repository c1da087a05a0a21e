#pragma once
// Linear analysis of a diagram (ELEMENTS.md 8): the Jacobian of x' = f(x) at
// a state, the static equilibrium, and the eigen-analysis that turns the
// Jacobian into natural frequencies, damping ratios and mode shapes.
//
// Generic over any diagram: it works on the continuous state vector, so a
// mechanism's (q, v) and any block states are analysed together. Time stays
// at Context::time, so sources give their values at that time; every other
// signal is recomputed from the state through EvaluateOutputs at each
// evaluation. Modes of nonsmooth blocks (stick/slip, contact, limits) are
// those settled at the initial state, or with FindEquilibrium those of the
// equilibrium found.
//
// One analysis, as pseudocode (what `mechflow modes` runs):
//   PrepareContext                   initial states, modes settled, time t_start
//   FindEquilibrium (optional)       damped Newton on x'(x) = 0, modes re-selected until they agree
//   A = StateJacobian                central differences, one column per state
//   ModalAnalysis(A)                 eigenvalues -> f, zeta; eigenvectors -> shapes

#include <complex>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "blocks/framework/diagram.h"

namespace mechflow::analysis {

using blocks::Context;
using blocks::Diagram;

// Sets up a Context for the diagram at t with the initial states and settled
// modes; `x` gets the initial continuous state (size max(1, num_states)).
void PrepareContext(const Diagram& diagram, double t, Context* ctx, std::vector<double>* x);

// x' at x (outputs evaluated first), at ctx->time.
void StateDerivative(const Diagram& diagram, Context* ctx, std::vector<double>* x, std::vector<double>* xdot);

// A = d(x')/dx at x and ctx->time, by central differences, column j from
//   (f(x + h_j e_j) - f(x - h_j e_j)) / (2 h_j),  h_j = eps^(1/3) max(1, |x_j|)
// (the step that balances the O(h^2) truncation error of central differences
// against the O(eps/h) rounding error; eps^(1/2) is the optimum for one-sided
// differences). The divisor is the difference of the two probes as stored, so
// a linear term comes out exact to rounding. Costs 2 n evaluations; leaves
// the context's outputs evaluated at x, with ctx->x = x.data() and ctx->xdot
// null. Throws SimulationError naming the state whose probe gave a
// non-finite x'.
Eigen::MatrixXd StateJacobian(const Diagram& diagram, Context* ctx, const std::vector<double>& x);

struct EquilibriumResult {
  int iterations = 0;    // Newton steps taken, over all rounds
  double residual = 0.0; // max |x'_i| at the equilibrium [state units / s]
  int rounds = 1;        // Newton solves: the first, and one after each change of modes
  std::vector<std::string> switched;  // "block.element" (or block) whose modes differ from the initial state's
};

// Finds a static equilibrium x'(x) = 0 from `x` (in place), in rounds:
//   repeat (at most 20 rounds)
//     solve x'(x) = 0 by damped Newton in the current modes
//     select the modes at x as a state at rest has them
//       (Block::UpdateModesAtRest, then SettleModes): a contact touches when
//       it penetrates, a sliding friction element sticks (with no stick
//       deflection yet), a stuck one holding more than its static limit
//       breaks away
//   until the modes (and the states they reset) are those x was found in.
// So the equilibrium returned carries the modes that agree with it, and the
// context is left in them. Each Newton solve:
//   loop
//     f = x'(x); A = StateJacobian(x)
//     done when |f_i| <= tolerance (1 + sum_j |A_ij| |x_j|) for every i,
//       i.e. x' is zero relative to the terms that balance in it
//     s = solution of A s = f in the range of A (A singular: what x' cannot
//       change, e.g. a stuck friction element's deflection less its travel,
//       stays, as in a damped transient; a direction both in the range and
//       the null space, a free undamped coordinate, is left alone)
//     alpha = 1, halved (at most 10 times) until |f(x - alpha s)|_2 <
//       (1 - 1e-4 alpha) |f(x)|_2; x -= alpha s
// For a mechanism, x = (q, v): the equilibrium has v = 0 and v' = 0, which
// this finds without knowing the split. Throws SimulationError with the
// residual and the steps taken when a solve does not converge within
// `max_iterations` steps, when no step along s decreases |f| (Newton stalled,
// e.g. the diagram is driven or drifts at a constant rate; after a change of
// modes the message names the elements switched), when x' is not finite, or
// when the modes do not settle within the rounds (naming the elements that
// still switch). Either way the context is left at `x`.
EquilibriumResult FindEquilibrium(const Diagram& diagram, Context* ctx, std::vector<double>* x,
                                  double tolerance = 1e-10, int max_iterations = 50);

enum class ModeKind {
  kOscillating,  // complex pair: frequency_hz > 0
  kDecaying,     // real lambda < 0: overdamped, decays at decay_rate
  kGrowing,      // real lambda > 0: unstable without oscillation
  kRigidBody,    // lambda = 0 (to 1e-9 of the largest |lambda|): a free motion
};

struct Mode {
  std::complex<double> eigenvalue;     // lambda [rad/s]
  ModeKind kind = ModeKind::kOscillating;
  double frequency_hz = 0.0;           // damped: |Im lambda| / 2 pi [Hz]
  double natural_frequency_hz = 0.0;   // undamped: |lambda| / 2 pi [Hz]
  double damping_ratio = 0.0;          // -Re lambda / |lambda|; 1 for a real decaying
                                       // eigenvalue, 0 for a rigid-body one
  double decay_rate = 0.0;             // -Re lambda [1/s]; time constant 1 / decay_rate
  std::vector<double> shape;           // per state: real part of the eigenvector,
                                       // scaled so its largest (normalising) component is 1
};

// Eigen-decomposition of A (Eigen::EigenSolver): one mode per complex-
// conjugate pair (the one with Im lambda > 0) and per real eigenvalue, sorted
// by natural frequency. Each eigenvector is divided by its largest-magnitude
// component among the states marked in `normalise_on` (e.g. the coordinates,
// not their rates; all states when it is empty), which makes that component
// exactly 1 and fixes the phase; `shape` keeps the real parts. For an undamped
// mode the rates' components are then imaginary (lambda times the
// coordinates'), so their real parts are 0.
std::vector<Mode> ModalAnalysis(const Eigen::MatrixXd& A, const std::vector<bool>& normalise_on = {});

// Second-order structure read off A: state i is a coordinate when its rate is
// exactly another state j (row i of A is the unit vector e_j, to 1e-9), as
// for q' = v of a mechanism joint or an integrator fed by another
// integrator's output; j is then a rate. Both vectors have one entry per state.
struct StateRoles {
  std::vector<bool> coordinate;
  std::vector<bool> rate;
};
StateRoles FindStateRoles(const Eigen::MatrixXd& A);

// "block.state" names of the continuous states, in state order.
std::vector<std::string> StateNames(const Diagram& diagram);

// What the linearisation at the context's state (outputs evaluated, as
// StateJacobian leaves them) took for each element that switches: one line
// per mechanism element with modes ("m.friction: stuck, held exactly: ...")
// and per friction_from_normal_force block: sliding, or regularised when
// its velocity input lies within three regularisation velocities of 0 (its
// tanh then acts as a viscous damper of slope mu_s N / v_reg). The
// frequencies hold only while these modes last.
std::vector<std::string> DescribeLinearisedModes(const Diagram& diagram, const Context& ctx);

}  // namespace mechflow::analysis
