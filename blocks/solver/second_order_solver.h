#pragma once
// SecondOrderSolver: CVODE's Newton systems solved in fewer unknowns when
// states come in pairs x_q' = x_v exactly (a joint coordinate and its
// velocity, Block::rate_pairs).
//
// Split the states into positions P (the q of each pair) and the rest R
// (velocities and every other state). The Newton matrix A = I - gamma J then
// has the rows P = [I  -gamma E] exactly, E picking each position's rate out
// of R, and x_P = b_P + gamma E x_R eliminates them:
//   (A_RR + gamma A_RP E) x_R = b_R - A_RP b_P.
// A mechanism without element states halves the system: an eighth of the
// factorisation's work, a quarter of each solve's. The rows P of CVODE's
// difference-quotient Jacobian (ones and zeros to within round-off) are not
// read; the exact ones are used.
//
// A SUNLinearSolver of the direct kind on CVODE's dense matrix: CVODE still
// forms A (its difference-quotient Jacobian, the reuse of J across steps,
// the scaling of the solution when gamma moved since the factorisation),
// and calls Setup and Solve here. The factorisation is Eigen's
// partial-pivoting LU, into storage allocated at construction.

#include <functional>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/LU>

#include "blocks/solver/sundials.h"

namespace mechflow::blocks {

class SecondOrderSolver {
 public:
  // `pairs` (position, rate) index the n states of `y`; no position may be
  // a rate (std::logic_error). `gamma()` is the gamma of the matrix CVODE
  // passes to Setup (CVodeGetCurrentGamma then).
  SecondOrderSolver(const sundials::Vector& y, const std::vector<std::pair<int, int>>& pairs,
                    std::function<double()> gamma, const sundials::Context& ctx);
  ~SecondOrderSolver();
  SecondOrderSolver(const SecondOrderSolver&) = delete;
  SecondOrderSolver& operator=(const SecondOrderSolver&) = delete;

  SUNMatrix matrix() const { return a_; }
  SUNLinearSolver solver() const { return ls_; }
  int reduced_size() const { return static_cast<int>(rest_.size()); }

 private:
  static int Setup(SUNLinearSolver ls, SUNMatrix a);
  static int Solve(SUNLinearSolver ls, SUNMatrix a, N_Vector x, N_Vector b, double tolerance);

  SUNMatrix a_ = nullptr;
  SUNLinearSolver ls_ = nullptr;
  std::function<double()> gamma_of_matrix_;
  std::vector<int> positions_, rest_;  // state indices of P and R
  std::vector<int> rate_in_rest_;      // per pair: its rate's place in R
  double gamma_ = 0.0;                 // of the last Setup
  Eigen::MatrixXd reduced_, rest_by_position_;  // A_RR + gamma A_RP E, A_RP
  Eigen::PartialPivLU<Eigen::MatrixXd> lu_;
  Eigen::VectorXd b_rest_, b_position_, x_rest_;
};

}  // namespace mechflow::blocks
