#pragma once
// Serial N_Vector and dense SUNMatrix operations compiled with the project,
// installed in place of NVECTOR_SERIAL's and SUNMATRIX_DENSE's own.
//
// Why: Debian 12's SUNDIALS 6.4.1 is built without optimisation (its CMake
// build type defaulted to none until SUNDIALS 7), so every vector operation
// of CVODE keeps each loop variable in memory: a weighted norm of 3000
// numbers took 12 % of a P3 run (bench/README.md) at N = 1000, and
// copying and scaling the 30 x 30 Newton matrix 25 % at N = 10.
//
// The operations compute exactly what NVECTOR_SERIAL computes -- the same
// special cases (c (x + y) when a = b, x - y when a = 1, b = -1, ...) and the
// same order of operations in every element and every sum -- so a run gives
// the same numbers, bit for bit, with either set. The fused operations
// (linear combination, scale-add-multi) follow, element by element, the
// sequence of linear sums SUNDIALS performs when a vector has none.
//
// Vectors cloned from one with these operations inherit them (N_VCloneEmpty
// copies the operations table); so do matrices (their clone is ours).

#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>

namespace mechflow::blocks::sundials {

// `v` must be an NVECTOR_SERIAL vector.
void UseCompiledVectorOps(N_Vector v);
// `a` must be a SUNMATRIX_DENSE matrix: zero, copy, A = cA + I, A = cA + B
// and clone become ours.
void UseCompiledMatrixOps(SUNMatrix a);

}  // namespace mechflow::blocks::sundials
