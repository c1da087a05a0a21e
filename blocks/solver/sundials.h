#pragma once
// Thin RAII owners for the SUNDIALS objects the simulator uses, and one
// helper that turns a failed call into an exception naming the call and its
// flag. Written against SUNDIALS 6.x (Debian 12 ships 6.4.1).

#include <string>

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "blocks/solver/sparsity.h"

namespace mechflow::blocks::sundials {

// Throws std::runtime_error("CVodeInit failed: CV_ILL_INPUT") when flag < 0.
void Check(int flag, const char* function);

// The symbolic name of a CVODE return flag ("CV_TOO_MUCH_WORK").
std::string CvodeFlagName(int flag);

class Context {
 public:
  Context();
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;
  SUNContext get() const { return ctx_; }

 private:
  SUNContext ctx_ = nullptr;
};

class Vector {
 public:
  Vector(sunindextype n, const Context& ctx);
  ~Vector();
  Vector(const Vector&) = delete;
  Vector& operator=(const Vector&) = delete;
  N_Vector get() const { return v_; }
  double* data() const { return data_; }  // kept: a serial vector's array never moves

 private:
  N_Vector v_ = nullptr;
  double* data_ = nullptr;
};

// A serial vector over `data` (not owned; N_VDestroy frees the vector alone),
// with the compiled operations (blocks/solver/compiled_ops.h), like Vector's.
N_Vector WrapArray(sunindextype n, double* data, const Context& ctx);

// Dense matrix plus dense direct linear solver for Newton's method.
class DenseSolver {
 public:
  DenseSolver(const Vector& y, const Context& ctx);
  ~DenseSolver();
  DenseSolver(const DenseSolver&) = delete;
  DenseSolver& operator=(const DenseSolver&) = delete;
  SUNMatrix matrix() const { return a_; }
  SUNLinearSolver solver() const { return ls_; }

 private:
  SUNMatrix a_ = nullptr;
  SUNLinearSolver ls_ = nullptr;
};

// Compressed-sparse-column matrix with a fixed pattern (set here, once) plus
// the KLU direct solver. KLU analyses the pattern at its first factorisation
// and only refactors afterwards.
class SparseSolver {
 public:
  SparseSolver(const Vector& y, const SparsityPattern& pattern, const Context& ctx);
  ~SparseSolver();
  SparseSolver(const SparseSolver&) = delete;
  SparseSolver& operator=(const SparseSolver&) = delete;
  SUNMatrix matrix() const { return a_; }
  SUNLinearSolver solver() const { return ls_; }
  double* values() const;  // the nonzeros, in the pattern's order

 private:
  SUNMatrix a_ = nullptr;
  SUNLinearSolver ls_ = nullptr;
};

// GMRES (SPGMR), preconditioned from the left; matrix-free: CVODE forms
// J v by a difference quotient, one right-hand side per iteration.
class KrylovSolver {
 public:
  KrylovSolver(const Vector& y, int max_krylov_dimension, const Context& ctx);
  ~KrylovSolver();
  KrylovSolver(const KrylovSolver&) = delete;
  KrylovSolver& operator=(const KrylovSolver&) = delete;
  SUNLinearSolver solver() const { return ls_; }

 private:
  SUNLinearSolver ls_ = nullptr;
};

// CVODE integrator memory (BDF).
class Cvode {
 public:
  explicit Cvode(const Context& ctx);
  ~Cvode();
  Cvode(const Cvode&) = delete;
  Cvode& operator=(const Cvode&) = delete;
  void* get() const { return mem_; }

 private:
  void* mem_ = nullptr;
};

}  // namespace mechflow::blocks::sundials
