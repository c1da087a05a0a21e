#pragma once
// What every hand-written reference program in bench/ needs around the
// CVODE C API: failed calls turned into exceptions, and the SUNDIALS objects
// of one run owned and freed in reverse order of creation. Deliberately
// independent of mechflow's own SUNDIALS wrappers (blocks/solver/sundials.h), so
// the references share no code with what they measure.

#include <stdexcept>
#include <string>

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>

namespace mechflow::bench::direct {

inline void Check(int flag, const char* function) {
  if (flag < 0) throw std::runtime_error(std::string(function) + " failed with flag " + std::to_string(flag));
}

template <typename T>
T* CheckPointer(T* p, const char* function) {
  if (!p) throw std::runtime_error(std::string(function) + " returned null");
  return p;
}

struct Solver {
  SUNContext ctx = nullptr;
  N_Vector y = nullptr;
  SUNMatrix a = nullptr;
  SUNLinearSolver ls = nullptr;
  void* cvode = nullptr;
  Solver() = default;
  Solver(const Solver&) = delete;
  Solver& operator=(const Solver&) = delete;
  ~Solver() {
    if (cvode) CVodeFree(&cvode);
    if (ls) SUNLinSolFree(ls);
    if (a) SUNMatDestroy(a);
    if (y) N_VDestroy(y);
    if (ctx) SUNContext_Free(&ctx);
  }
};

}  // namespace mechflow::bench::direct
