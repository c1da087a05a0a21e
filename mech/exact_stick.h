#pragma once
// Exact stick: the holding forces of the friction elements that stick
// exactly (ForceElement::StuckExactly; the Frictional element's
// `exact_stick`, docs/ELEMENTS.md 3.6), instead of a stick spring that must
// first deflect to carry a load.
//
// While k elements stick, their relative accelerations a are affine in their
// holding forces f: a = a0 + S f, where S is the inverse mass the elements
// see along their lines (J M^-1 J^T on the loops' manifold: symmetric,
// positive semi-definite). The dynamics are linear in the loads, so the
// mechanism measures a0 with every holding force at zero and each column of
// S by one more pass with one force applied, then solves S f = -a0: k + 2
// dynamics passes per evaluation while anything sticks, one otherwise. This
// is the friction state machine of Modelica's library (the stuck motion is
// constrained, the force follows from the balance) without a DAE solver.
// Directions in which S is singular (two elements holding the same motion,
// a motion that a loop locks already) get no force: rigid bodies do not
// decide how redundant holds share a load, and none is made up.

#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>

namespace mechflow::mech {

// Per-run storage: sized once for the mechanism's exact-stick elements.
struct StickWorkspace {
  StickWorkspace(int num_elements, int num_exact);

  std::vector<double> force;  // per element: its holding force while stuck exactly, else 0
  std::vector<double> probe;  // per element: the force of its probe pass (the size of its last holding force)
  std::vector<int> stuck;     // the elements stuck exactly in this evaluation
  Eigen::MatrixXd S;          // num_exact x num_exact; rows and columns past the stuck ones are padding
  Eigen::VectorXd a0, f;
  Eigen::LDLT<Eigen::MatrixXd> ldlt;
};

// Solves S f = -a0 over the first stuck.size() rows of ws->S and ws->a0
// (filled by the caller); writes ws->f. Pivots at round-off get no force.
void SolveHoldingForces(StickWorkspace* ws);

}  // namespace mechflow::mech
