#pragma once
// AlgebraicLoop: a cycle of direct feedthrough, solved at every evaluation.
//
// A strongly connected component of the feedthrough graph has no evaluation
// order. The builder cuts it at a few output ports, the *tears*: given values
// z for the tear outputs, the other ports of the loop (the *inner* ports) can
// be computed in order, and then the tears themselves, which gives G(z). The
// loop is solved when G(z) = z. Newton's method on r(z) = G(z) - z:
//
//   z        := the tear values of the last evaluation (warm start)
//   repeat:  r := G(z) - z; stop when every |r_i| <= rel |z_i| + abs
//            J := dG/dz by forward differences, kept from solve to solve
//                 and corrected by Broyden's update after slow steps
//            z := z - (J - I)^-1 r
//
// A loop that is linear in its signals (a reaction force through a friction
// coefficient) converges in one step once J is known; a stale J from an
// earlier evaluation is refreshed when the residual stops shrinking fast.
// When (J - I) is singular the loop has no unique solution (e.g. y = y + 1),
// and a loop that does not converge in kMaxIterations ends the step with a
// SimulationError naming its hops. When, over those iterations, the residual
// kept its sign and a Jacobian showed a loop gain (largest real eigenvalue of
// J = dG/dz; for one unknown, the derivative of the loop map) above 1, the
// loop returns more than it receives and has no solution: a self-locking
// wedge or brake, whose friction force feeds its own normal force with gain
// mu c / b > 1. That is a NoSolutionError, with the gain.
//
// The workspace (Newton arrays, the kept Jacobian, the counters) is the
// run's: made with the Context (MakeScratch, sized there), so Solve allocates
// nothing and one built loop may be solved by several runs at once.

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "blocks/framework/block_context.h"
#include "mech/errors.h"

namespace mechflow::blocks {

class Diagram;

// An algebraic loop with no solution at some instant: the model's fault, not
// the step size's, so the solver adds no hint about step sizes.
class NoSolutionError : public SimulationError {
 public:
  using SimulationError::SimulationError;
};

// One output port of one block. In a diagram's schedule, `loop` >= 0 marks an
// entry that stands for the whole algebraic loop of that index (the port is
// the loop's first tear).
struct OutputNode {
  int block = 0;
  int port = 0;
  int loop = -1;
};

// Counters over a run, for reports.
struct LoopStats {
  long solves = 0;
  long iterations = 0;   // Newton steps taken
  long evaluations = 0;  // evaluations of the loop's ports (including Jacobian columns)
  long jacobians = 0;
  double worst_residual = 0.0;  // largest relative residual accepted
};

class AlgebraicLoop {
 public:
  // Convergence: every tear value changes by less than kRelativeTolerance of
  // its size plus kAbsoluteTolerance (in its own unit).
  static constexpr double kRelativeTolerance = 1e-10;
  static constexpr double kAbsoluteTolerance = 1e-12;
  static constexpr int kMaxIterations = 30;

  // `tear_offsets`/`tear_widths`: where each tear's values sit in the signals.
  // `copies`: (unknown, signal) pairs of further slots that get the tear
  // values z -- the input copy of a block that feeds itself, which cannot
  // read the slot it is writing (see DiagramBuilder::LayOut).
  // `port` names one port of the loop ("s.y"), `hops` one line per hop of a
  // cycle through it ("\n  a.y -> s.u1 (feeds s.y directly) at file:line").
  // `index`: the loop's in the diagram (Diagram::loops()), where its scratch
  // sits in Context::loop_scratch.
  AlgebraicLoop(int index, std::vector<OutputNode> inner, std::vector<OutputNode> tears,
                const std::vector<int>& tear_offsets, const std::vector<int>& tear_widths,
                std::vector<std::pair<int, int>> copies, std::string port, std::string hops);

  const std::vector<OutputNode>& inner() const { return inner_; }
  const std::vector<OutputNode>& tears() const { return tears_; }
  int num_unknowns() const { return static_cast<int>(slot_.size()); }
  const std::string& port() const { return port_; }
  // " through s.y:" and the hops.
  const std::string& description() const { return description_; }
  // The counters of the run that `run` holds (zero until it is prepared).
  const LoopStats& stats(const Context& run) const;

  // The loop's scratch for a new run (InitializeStates makes one per loop).
  std::unique_ptr<BlockScratch> MakeScratch() const;

  // Computes every port of the loop so that the tears agree with what they
  // feed. Throws SimulationError when it cannot.
  void Solve(const Diagram& d, Context* ctx) const;

 private:
  // Writes z into the tear signals, evaluates inner ports then tears, and
  // reads G(z) into g.
  struct Scratch;
  Scratch& ScratchOf(Context* ctx) const;
  void Evaluate(const Diagram& d, Context* ctx, Scratch& s, const Eigen::VectorXd& z, Eigen::VectorXd* g) const;
  void UpdateJacobian(const Diagram& d, Context* ctx, Scratch& s) const;
  double PivotRatio(const Scratch& s) const;
  bool Converged(const Eigen::VectorXd& z, const Eigen::VectorXd& r, double* worst) const;
  [[noreturn]] void Fail(const Context& ctx, Scratch& s, const std::string& why, bool no_solution = false) const;
  // After kMaxIterations: why, as words, and whether the loop has no solution.
  std::string Diagnose(const Scratch& s, double worst, bool* no_solution) const;

  int index_ = 0;
  std::vector<OutputNode> inner_, tears_;
  std::vector<int> slot_;  // unknown k lives at signals[slot_[k]]
  std::vector<std::pair<int, int>> copies_;  // (unknown, signal) also set to z
  std::string port_, description_;

};

}  // namespace mechflow::blocks
