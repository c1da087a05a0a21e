#include "mech/exact_stick.h"

#include <algorithm>
#include <cmath>

namespace mechflow::mech {
namespace {

// Pivots below kRedundant * (largest) are round-off: directions in which
// the holds are redundant. (Holds mix units -- forces, moments -- so the
// bound stays at round-off.)
constexpr double kRedundant = 1e-12;
// A hold no force moves: its S_ii below kUnmoved * (largest S_jj), no
// more than round-off; it is unholdable when its residual acceleration is
// above kResidual * (the accelerations in play) -- not round-off, nor the
// second-order disagreement of redundant holds slightly off rest.
constexpr double kUnmoved = 1e-15;
constexpr double kResidual = 1e-3;

// Symmetric by theory; averaged so round-off cannot make it otherwise. The
// padding takes the largest diagonal, which keeps the pivots of the stuck
// block on their own scale (fixed size: no allocation).
void Symmetrise(StickWorkspace* ws, int k) {
  const int n = static_cast<int>(ws->S.rows());
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < i; ++j) ws->S(i, j) = ws->S(j, i) = 0.5 * (ws->S(i, j) + ws->S(j, i));
  const double scale = k > 0 ? ws->S.diagonal().head(k).cwiseAbs().maxCoeff() : 1.0;
  for (int i = k; i < n; ++i) {
    ws->S.row(i).setZero();
    ws->S.col(i).setZero();
    ws->S(i, i) = scale > 0.0 ? scale : 1.0;
    ws->a0(i) = 0.0;
  }
}

// S f = -a0 by LDL^T; pivots at round-off (redundant holds) get no force.
void Solve(StickWorkspace* ws) {
  const int n = static_cast<int>(ws->S.rows());
  ws->ldlt.compute(ws->S);
  const auto d = ws->ldlt.vectorD();
  const double largest = n > 0 ? d.cwiseAbs().maxCoeff() : 0.0;
  // step by step, in place: no temporaries
  ws->f = -ws->a0;
  ws->f = ws->ldlt.transpositionsP() * ws->f;
  ws->ldlt.matrixL().solveInPlace(ws->f);
  // 1/d, damped below the round-off bound: a pivot that shrinks toward it as
  // redundant holds line up (a wheel set's two rims rocking level) gives a
  // force that fades to none continuously. Cut off there, the force jumped
  // where the integrator kept returning, and its step fell to nothing.
  const double floor = kRedundant * largest;
  for (int i = 0; i < n; ++i) ws->f(i) = d(i) > 0.0 ? ws->f(i) * d(i) / (d(i) * d(i) + floor * floor) : 0.0;
  ws->ldlt.matrixU().solveInPlace(ws->f);
  ws->f = ws->ldlt.transpositionsP().transpose() * ws->f;
}

// A stuck hold that no force moves (its S_ii is round-off) but that the
// forces leave accelerating; else -1.
int Unholdable(const StickWorkspace& ws, int k) {
  double scale = 0.0, largest_diagonal = 0.0;
  for (int i = 0; i < k; ++i) {
    scale = std::max(scale, std::abs(ws.a0(i)));
    largest_diagonal = std::max(largest_diagonal, std::abs(ws.S(i, i)));
    for (int j = 0; j < k; ++j) scale = std::max(scale, std::abs(ws.S(i, j) * ws.f(j)));
  }
  for (int i = 0; i < k; ++i) {
    if (ws.S(i, i) > kUnmoved * largest_diagonal) continue;
    double residual = ws.a0(i);
    for (int j = 0; j < k; ++j) residual += ws.S(i, j) * ws.f(j);
    if (std::abs(residual) > kResidual * scale) return i;
  }
  return -1;
}

}  // namespace

StickWorkspace::StickWorkspace(int num_holds)
    : force(num_holds, 0.0),
      probe(num_holds, 1.0),
      S(Eigen::MatrixXd::Identity(num_holds, num_holds)),
      a0(Eigen::VectorXd::Zero(num_holds)),
      f(Eigen::VectorXd::Zero(num_holds)),
      ldlt(num_holds) {
  stuck.reserve(num_holds);
}

int SolveHoldingForces(StickWorkspace* ws) {
  const int k = static_cast<int>(ws->stuck.size());
  Symmetrise(ws, k);
  Solve(ws);
  return Unholdable(*ws, k);
}

}  // namespace mechflow::mech
