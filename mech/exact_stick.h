#pragma once
// Exact stick: the holding forces of the holds that stick exactly
// (ForceElement::StuckExactly: the Frictional element's `exact_stick`,
// docs/ELEMENTS.md 3.6, and the contact points of contacts with
// stick="exact", two holds each), instead of a stick spring that must
// first deflect to carry a load.
//
// While k holds stick, their relative accelerations a are affine in their
// holding forces f: a = a0 + S f, where S is the inverse mass the holds
// see along their directions (J M^-1 J^T on the loops' manifold:
// symmetric, positive semi-definite). The dynamics are linear in the
// loads, so the mechanism measures a0 with every holding force at zero and
// each column of S by one more pass with one force applied, then solves
// S f = -a0: k + 2 dynamics passes per evaluation while anything sticks,
// one otherwise. This is the friction state machine of Modelica's library
// (the stuck motion is constrained, the force follows from the balance)
// without a DAE solver.
//
// Redundant holds (two holding one motion: two friction elements on one
// slide, the joints of a loop with one degree of freedom, two rims of one
// wheel set on the ground) leave the forces undecided by the balance; rigid
// bodies do not say how they share a load, and none is made up: directions
// in which S is singular get no force (one of the redundant holds carries
// it), and as S nears singular the force in that direction fades to none
// continuously rather than at a cut-off the integrator could not step over.
// A hold whose motion no force changes and that the rest of the mechanism
// still drives (a prescribed motion across a stuck contact) has no holding
// force at all: SolveHoldingForces reports it.

#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>

namespace mechflow::mech {

// Per-run storage: sized once for the mechanism's holds (Mechanism::num_holds).
struct StickWorkspace {
  explicit StickWorkspace(int num_holds);

  std::vector<double> force;   // per hold: its holding force while stuck exactly, else 0
  std::vector<double> probe;   // per hold: the force of its probe pass (its holding force's size when the last step ended)
  std::vector<int> stuck;      // the holds stuck exactly in this evaluation
  Eigen::MatrixXd S;           // num_holds x num_holds; rows and columns past the stuck ones are padding
  Eigen::VectorXd a0, f;
  Eigen::LDLT<Eigen::MatrixXd> ldlt;
};

// Solves S f = -a0 over the first stuck.size() rows of ws->S and ws->a0
// (filled by the caller); writes
// ws->f. Returns -1, or the position in ws->stuck of a hold that no force
// moves but that accelerates all the same.
int SolveHoldingForces(StickWorkspace* ws);

}  // namespace mechflow::mech
