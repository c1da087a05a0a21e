#include "blocks/solver/second_order_solver.h"

#include <cmath>
#include <stdexcept>

#include "blocks/solver/compiled_ops.h"

namespace mechflow::blocks {

SecondOrderSolver::SecondOrderSolver(const sundials::Vector& y, const std::vector<std::pair<int, int>>& pairs,
                                     std::function<double()> gamma, const sundials::Context& ctx)
    : gamma_of_matrix_(std::move(gamma)) {
  const int n = static_cast<int>(N_VGetLength(y.get()));
  std::vector<int> role(n, -1);  // -1: in R; otherwise the pair whose position it is
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const auto [position, rate] = pairs[k];
    if (position < 0 || position >= n || rate < 0 || rate >= n || role[position] >= 0)
      throw std::logic_error("SecondOrderSolver: bad rate pair");
    role[position] = static_cast<int>(k);
  }
  std::vector<int> place(n, -1);
  for (int i = 0; i < n; ++i) {
    if (role[i] >= 0) continue;
    place[i] = static_cast<int>(rest_.size());
    rest_.push_back(i);
  }
  for (const auto& [position, rate] : pairs) {
    if (place[rate] < 0) throw std::logic_error("SecondOrderSolver: a position is another pair's rate");
    positions_.push_back(position);
    rate_in_rest_.push_back(place[rate]);
  }
  const Eigen::Index r = static_cast<Eigen::Index>(rest_.size()), p = static_cast<Eigen::Index>(positions_.size());
  reduced_.setZero(r, r);
  rest_by_position_.setZero(r, p);
  lu_ = Eigen::PartialPivLU<Eigen::MatrixXd>(r);
  b_rest_.setZero(r);
  b_position_.setZero(p);
  x_rest_.setZero(r);

  a_ = SUNDenseMatrix(n, n, ctx.get());
  if (!a_) throw std::runtime_error("SUNDenseMatrix failed");
  sundials::UseCompiledMatrixOps(a_);  // CVODE copies and scales it at every setup
  ls_ = SUNLinSolNewEmpty(ctx.get());
  if (!ls_) {
    SUNMatDestroy(a_);
    throw std::runtime_error("SUNLinSolNewEmpty failed");
  }
  ls_->content = this;
  ls_->ops->gettype = [](SUNLinearSolver) { return SUNLINEARSOLVER_DIRECT; };
  ls_->ops->getid = [](SUNLinearSolver) { return SUNLINEARSOLVER_CUSTOM; };
  ls_->ops->setup = &SecondOrderSolver::Setup;
  ls_->ops->solve = &SecondOrderSolver::Solve;
}

SecondOrderSolver::~SecondOrderSolver() {
  SUNLinSolFreeEmpty(ls_);
  SUNMatDestroy(a_);
}

int SecondOrderSolver::Setup(SUNLinearSolver ls, SUNMatrix a) {
  auto& self = *static_cast<SecondOrderSolver*>(ls->content);
  self.gamma_ = self.gamma_of_matrix_();
  if (!std::isfinite(self.gamma_)) return SUNLS_MEM_FAIL;
  const double* values = SUNDenseMatrix_Data(a);
  const sunindextype n = SUNDenseMatrix_Rows(a);
  const auto entry = [&](int row, int column) { return values[column * n + row]; };  // column-major
  const Eigen::Index r = self.reduced_.rows();
  for (Eigen::Index k = 0; k < r; ++k)
    for (Eigen::Index i = 0; i < r; ++i) self.reduced_(i, k) = entry(self.rest_[i], self.rest_[k]);
  for (std::size_t p = 0; p < self.positions_.size(); ++p) {
    for (Eigen::Index i = 0; i < r; ++i) self.rest_by_position_(i, p) = entry(self.rest_[i], self.positions_[p]);
    self.reduced_.col(self.rate_in_rest_[p]) += self.gamma_ * self.rest_by_position_.col(p);
  }
  self.lu_.compute(self.reduced_);
  // a zero or non-finite pivot: recoverable (CVODE retries with a smaller step)
  const auto pivots = self.lu_.matrixLU().diagonal();
  for (Eigen::Index i = 0; i < r; ++i)
    if (!(std::abs(pivots(i)) > 0.0) || !std::isfinite(pivots(i))) return SUNLS_LUFACT_FAIL;
  return SUNLS_SUCCESS;
}

int SecondOrderSolver::Solve(SUNLinearSolver ls, SUNMatrix, N_Vector x, N_Vector b, double) {
  auto& self = *static_cast<SecondOrderSolver*>(ls->content);
  const double* in = N_VGetArrayPointer(b);
  double* out = N_VGetArrayPointer(x);
  const Eigen::Index r = self.reduced_.rows();
  for (Eigen::Index i = 0; i < r; ++i) self.b_rest_(i) = in[self.rest_[i]];
  for (std::size_t p = 0; p < self.positions_.size(); ++p) self.b_position_(p) = in[self.positions_[p]];
  self.b_rest_.noalias() -= self.rest_by_position_ * self.b_position_;
  self.x_rest_.noalias() = self.lu_.solve(self.b_rest_);
  for (Eigen::Index i = 0; i < r; ++i) out[self.rest_[i]] = self.x_rest_(i);
  for (std::size_t p = 0; p < self.positions_.size(); ++p)
    out[self.positions_[p]] = self.b_position_(p) + self.gamma_ * self.x_rest_(self.rate_in_rest_[p]);
  return SUNLS_SUCCESS;
}

}  // namespace mechflow::blocks
