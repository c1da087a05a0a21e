#include "blocks/solver/sundials.h"

#include <cstdlib>
#include <stdexcept>

#include <sunlinsol/sunlinsol_klu.h>
#include <sunlinsol/sunlinsol_spgmr.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "blocks/solver/compiled_ops.h"

namespace mechflow::blocks::sundials {

std::string CvodeFlagName(int flag) {
  char* name = CVodeGetReturnFlagName(flag);  // malloc'ed by CVODE
  std::string out = name ? name : "unknown flag " + std::to_string(flag);
  std::free(name);
  return out;
}

void Check(int flag, const char* function) {
  if (flag < 0) throw std::runtime_error(std::string(function) + " failed: " + CvodeFlagName(flag));
}

Context::Context() {
  if (SUNContext_Create(nullptr, &ctx_) != 0) throw std::runtime_error("SUNContext_Create failed");
}
Context::~Context() { SUNContext_Free(&ctx_); }

Vector::Vector(sunindextype n, const Context& ctx) : v_(N_VNew_Serial(n, ctx.get())) {
  if (!v_) throw std::runtime_error("N_VNew_Serial failed");
  data_ = N_VGetArrayPointer(v_);
  UseCompiledVectorOps(v_);  // and so CVODE's clones of it
}
Vector::~Vector() { N_VDestroy(v_); }

N_Vector WrapArray(sunindextype n, double* data, const Context& ctx) {
  N_Vector v = N_VMake_Serial(n, data, ctx.get());
  if (!v) throw std::runtime_error("N_VMake_Serial failed");
  UseCompiledVectorOps(v);
  return v;
}

DenseSolver::DenseSolver(const Vector& y, const Context& ctx) {
  const sunindextype n = N_VGetLength(y.get());
  a_ = SUNDenseMatrix(n, n, ctx.get());
  if (!a_) throw std::runtime_error("SUNDenseMatrix failed");
  UseCompiledMatrixOps(a_);
  ls_ = SUNLinSol_Dense(y.get(), a_, ctx.get());
  if (!ls_) {
    SUNMatDestroy(a_);
    throw std::runtime_error("SUNLinSol_Dense failed");
  }
}
DenseSolver::~DenseSolver() {
  SUNLinSolFree(ls_);
  SUNMatDestroy(a_);
}

namespace {

// KLU's initialisation only asks for a fresh symbolic analysis and
// factorisation at the next setup; CVodeReInit initialises the linear solver
// after every event. The pattern is the run's, fixed, so the analysis stays
// valid; a refactorisation with the old pivot order is checked by KLU's
// condition estimate in every setup, which factors afresh when it degrades.
int KeepKluAnalysis(SUNLinearSolver) { return SUNLS_SUCCESS; }

}  // namespace

SparseSolver::SparseSolver(const Vector& y, const SparsityPattern& pattern, const Context& ctx) {
  const sunindextype n = N_VGetLength(y.get());
  if (n != pattern.n) throw std::logic_error("sparsity pattern and state vector differ in size");
  a_ = SUNSparseMatrix(n, n, pattern.nonzeros(), CSC_MAT, ctx.get());
  if (!a_) throw std::runtime_error("SUNSparseMatrix failed");
  sunindextype* start = SUNSparseMatrix_IndexPointers(a_);
  sunindextype* rows = SUNSparseMatrix_IndexValues(a_);
  for (sunindextype j = 0; j <= n; ++j) start[j] = pattern.column_start[j];
  for (int k = 0; k < pattern.nonzeros(); ++k) rows[k] = pattern.rows[k];
  ls_ = SUNLinSol_KLU(y.get(), a_, ctx.get());
  if (!ls_) {
    SUNMatDestroy(a_);
    throw std::runtime_error("SUNLinSol_KLU failed");
  }
  ls_->ops->initialize = KeepKluAnalysis;
}
SparseSolver::~SparseSolver() {
  SUNLinSolFree(ls_);
  SUNMatDestroy(a_);
}
double* SparseSolver::values() const { return SUNSparseMatrix_Data(a_); }

KrylovSolver::KrylovSolver(const Vector& y, int max_krylov_dimension, const Context& ctx)
    : ls_(SUNLinSol_SPGMR(y.get(), SUN_PREC_LEFT, max_krylov_dimension, ctx.get())) {
  if (!ls_) throw std::runtime_error("SUNLinSol_SPGMR failed");
}
KrylovSolver::~KrylovSolver() { SUNLinSolFree(ls_); }

Cvode::Cvode(const Context& ctx) : mem_(CVodeCreate(CV_BDF, ctx.get())) {
  if (!mem_) throw std::runtime_error("CVodeCreate failed");
}
Cvode::~Cvode() { CVodeFree(&mem_); }

}  // namespace mechflow::blocks::sundials
