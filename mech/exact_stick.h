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
// Redundant holds (S singular: the four corners of a box holding its three
// in-plane motions, two friction elements on one slide) leave the forces
// undecided by the balance; rigid bodies do not say how they share a load.
// The forces taken are then those of least sum f_i^2 / w_i, the holds'
// weights (ForceElement::HoldWeight: the loads their static limits scale
// with, a contact point's normal force), so that a load shared by redundant
// holds reaches every static limit at once, as it does when the contacts'
// compliance shares it. Redundant holds may also disagree at second order
// (the corners of a box that rocks on its contacts cannot all keep still
// tangentially): the forces then hold them in the least-squares sense. A
// hold whose motion no force can change and that the rest of the mechanism
// still drives (a prescribed motion across a stuck contact) has no holding
// force at all: SolveHoldingForces reports it.

#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Eigenvalues>

namespace mechflow::mech {

// Per-run storage: sized once for the mechanism's holds (Mechanism::num_holds).
struct StickWorkspace {
  explicit StickWorkspace(int num_holds);

  std::vector<double> force;   // per hold: its holding force while stuck exactly, else 0
  std::vector<double> probe;   // per hold: the force of its probe pass (the size of its last holding force)
  std::vector<int> stuck;      // the holds stuck exactly in this evaluation
  Eigen::MatrixXd S;           // num_holds x num_holds; rows and columns past the stuck ones are padding
  Eigen::VectorXd a0, f;
  Eigen::VectorXd weight;      // per stuck hold (only read when S is singular)
  Eigen::LDLT<Eigen::MatrixXd> ldlt;
  Eigen::MatrixXd scaled;      // D S D, D = diag(sqrt(weight))
  Eigen::VectorXd rhs;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen;
};

// Solves S f = -a0 over the first stuck.size() rows of ws->S and ws->a0
// (and, when S is singular, ws->weight; all filled by the caller); writes
// ws->f. Returns -1, or the position in ws->stuck of a hold that no force
// moves but that accelerates all the same.
int SolveHoldingForces(StickWorkspace* ws);

}  // namespace mechflow::mech
