#include "mech/exact_stick.h"

#include <algorithm>
#include <cmath>

namespace mechflow::mech {
namespace {

// Pivots below kNoise * (largest) are round-off: a redundant hold.
constexpr double kNoise = 1e-12;

}  // namespace

StickWorkspace::StickWorkspace(int num_elements, int num_exact)
    : force(num_elements, 0.0),
      probe(num_elements, 1.0),
      S(Eigen::MatrixXd::Identity(num_exact, num_exact)),
      a0(Eigen::VectorXd::Zero(num_exact)),
      f(Eigen::VectorXd::Zero(num_exact)),
      ldlt(num_exact) {
  stuck.reserve(num_exact);
}

void SolveHoldingForces(StickWorkspace* ws) {
  const int n = static_cast<int>(ws->S.rows()), k = static_cast<int>(ws->stuck.size());
  // Symmetric by theory; averaged so round-off cannot make it otherwise.
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < i; ++j) ws->S(i, j) = ws->S(j, i) = 0.5 * (ws->S(i, j) + ws->S(j, i));
  // Padding with the largest diagonal keeps the pivots of the stuck block
  // on their own scale (fixed size: no allocation).
  const double scale = k > 0 ? ws->S.diagonal().head(k).cwiseAbs().maxCoeff() : 1.0;
  for (int i = k; i < n; ++i) {
    ws->S.row(i).setZero();
    ws->S.col(i).setZero();
    ws->S(i, i) = scale > 0.0 ? scale : 1.0;
    ws->a0(i) = 0.0;
  }
  ws->ldlt.compute(ws->S);
  const auto d = ws->ldlt.vectorD();
  const double largest = n > 0 ? d.cwiseAbs().maxCoeff() : 0.0;
  ws->f = -ws->a0;
  ws->f = ws->ldlt.transpositionsP() * ws->f;  // in place for transpositions
  ws->ldlt.matrixL().solveInPlace(ws->f);
  for (int i = 0; i < n; ++i) ws->f(i) = d(i) > kNoise * largest ? ws->f(i) / d(i) : 0.0;
  ws->ldlt.matrixU().solveInPlace(ws->f);
  ws->f = ws->ldlt.transpositionsP().transpose() * ws->f;
}

}  // namespace mechflow::mech
