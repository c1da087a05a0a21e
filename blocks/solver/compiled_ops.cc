#include "blocks/solver/compiled_ops.h"

#include <algorithm>
#include <cmath>

namespace mechflow::blocks::sundials {
namespace {

// Every loop below writes z[i] from the i-th elements alone, so z may be one
// of the operands (as NVECTOR_SERIAL allows), except where said.

double* Data(N_Vector v) { return NV_DATA_S(v); }
sunindextype Length(N_Vector v) { return NV_LENGTH_S(v); }

// y <- a x + y
void Axpy(double a, const double* x, double* y, sunindextype n) {
  if (a == 1.0) {
    for (sunindextype i = 0; i < n; ++i) y[i] += x[i];
  } else if (a == -1.0) {
    for (sunindextype i = 0; i < n; ++i) y[i] -= x[i];
  } else {
    for (sunindextype i = 0; i < n; ++i) y[i] += a * x[i];
  }
}

// z = a x + b y, by NVECTOR_SERIAL's cases in its order (each case rounds as
// it does there: c (x + y) is not c x + c y).
void LinearSum(double a, N_Vector xv, double b, N_Vector yv, N_Vector zv) {
  const sunindextype n = Length(xv);
  const double* x = Data(xv);
  const double* y = Data(yv);
  double* z = Data(zv);
  if (b == 1.0 && zv == yv) return Axpy(a, x, z, n);
  if (a == 1.0 && zv == xv) return Axpy(b, y, z, n);
  auto each = [&](auto f) {
    for (sunindextype i = 0; i < n; ++i) z[i] = f(x[i], y[i]);
  };
  if (a == 1.0 && b == 1.0) return each([](double p, double q) { return p + q; });
  if (a == 1.0 && b == -1.0) return each([](double p, double q) { return p - q; });
  if (a == -1.0 && b == 1.0) return each([](double p, double q) { return q - p; });
  if (a == 1.0) return each([b](double p, double q) { return b * q + p; });
  if (b == 1.0) return each([a](double p, double q) { return a * p + q; });
  if (a == -1.0) return each([b](double p, double q) { return b * q - p; });
  if (b == -1.0) return each([a](double p, double q) { return a * p - q; });
  if (a == b) return each([a](double p, double q) { return a * (p + q); });
  if (a == -b) return each([a](double p, double q) { return a * (p - q); });
  each([a, b](double p, double q) { return a * p + b * q; });
}

// z = c x (a copy or a negation for c = 1 or -1: the same numbers)
void Scale(double c, N_Vector xv, N_Vector zv) {
  const sunindextype n = Length(xv);
  const double* x = Data(xv);
  double* z = Data(zv);
  for (sunindextype i = 0; i < n; ++i) z[i] = c * x[i];
}

void Const(double c, N_Vector zv) {
  double* z = Data(zv);
  for (sunindextype i = 0, n = Length(zv); i < n; ++i) z[i] = c;
}

void Prod(N_Vector xv, N_Vector yv, N_Vector zv) {
  const double *x = Data(xv), *y = Data(yv);
  double* z = Data(zv);
  for (sunindextype i = 0, n = Length(xv); i < n; ++i) z[i] = x[i] * y[i];
}

void Div(N_Vector xv, N_Vector yv, N_Vector zv) {
  const double *x = Data(xv), *y = Data(yv);
  double* z = Data(zv);
  for (sunindextype i = 0, n = Length(xv); i < n; ++i) z[i] = x[i] / y[i];
}

void Abs(N_Vector xv, N_Vector zv) {
  const double* x = Data(xv);
  double* z = Data(zv);
  for (sunindextype i = 0, n = Length(xv); i < n; ++i) z[i] = std::fabs(x[i]);
}

void Inv(N_Vector xv, N_Vector zv) {
  const double* x = Data(xv);
  double* z = Data(zv);
  for (sunindextype i = 0, n = Length(xv); i < n; ++i) z[i] = 1.0 / x[i];
}

void AddConst(N_Vector xv, double b, N_Vector zv) {
  const double* x = Data(xv);
  double* z = Data(zv);
  for (sunindextype i = 0, n = Length(xv); i < n; ++i) z[i] = x[i] + b;
}

void Compare(double c, N_Vector xv, N_Vector zv) {
  const double* x = Data(xv);
  double* z = Data(zv);
  for (sunindextype i = 0, n = Length(xv); i < n; ++i) z[i] = std::fabs(x[i]) >= c ? 1.0 : 0.0;
}

double MaxNorm(N_Vector xv) {
  const double* x = Data(xv);
  double max = 0.0;
  for (sunindextype i = 0, n = Length(xv); i < n; ++i)
    if (std::fabs(x[i]) > max) max = std::fabs(x[i]);
  return max;
}

double Min(N_Vector xv) {
  const double* x = Data(xv);
  double min = x[0];
  for (sunindextype i = 1, n = Length(xv); i < n; ++i)
    if (x[i] < min) min = x[i];
  return min;
}

// the sum in index order, as NVECTOR_SERIAL adds it
double WSqrSum(N_Vector xv, N_Vector wv) {
  const double *x = Data(xv), *w = Data(wv);
  double sum = 0.0;
  for (sunindextype i = 0, n = Length(xv); i < n; ++i) {
    const double p = x[i] * w[i];
    sum += p * p;
  }
  return sum;
}

double WrmsNorm(N_Vector xv, N_Vector wv) {
  const double mean = WSqrSum(xv, wv) / static_cast<double>(Length(xv));
  return mean <= 0.0 ? 0.0 : std::sqrt(mean);
}

// z = sum_k c_k X_k. SUNDIALS without a fused operation scales X_0 into z,
// then adds c_k X_k for k = 1, 2, ...; here each element takes the same
// steps in one pass. When z is one of X_1, X_2, ..., those steps read a z
// already overwritten: they are taken vector by vector, as there.
int LinearCombination(int nvec, double* c, N_Vector* X, N_Vector zv) {
  constexpr int kMaxVectors = 16;  // CVODE combines at most q_max + 1 = 6
  bool in_one_pass = nvec <= kMaxVectors;
  for (int k = 1; k < nvec; ++k) in_one_pass = in_one_pass && X[k] != zv;
  if (!in_one_pass) {
    Scale(c[0], X[0], zv);
    for (int k = 1; k < nvec; ++k) LinearSum(c[k], X[k], 1.0, zv, zv);
    return 0;
  }
  const double* x[kMaxVectors];
  for (int k = 0; k < nvec; ++k) x[k] = Data(X[k]);
  double* z = Data(zv);
  for (sunindextype i = 0, n = Length(zv); i < n; ++i) {
    double sum = c[0] * x[0][i];
    for (int k = 1; k < nvec; ++k) sum += c[k] * x[k][i];
    z[i] = sum;
  }
  return 0;
}

// Z_k = a_k x + Y_k, vector after vector as SUNDIALS's linear sums: a Z_k
// that is x changes x for the later k there and here.
int ScaleAddMulti(int nvec, double* a, N_Vector xv, N_Vector* Y, N_Vector* Z) {
  const double* x = Data(xv);
  const sunindextype n = Length(xv);
  for (int k = 0; k < nvec; ++k) {
    const double* y = Data(Y[k]);
    double* z = Data(Z[k]);
    const double ak = a[k];
    for (sunindextype i = 0; i < n; ++i) z[i] = ak * x[i] + y[i];
  }
  return 0;
}

// Dense matrices, column-major: with equal shapes, element k of one is
// element k of the other.

bool SameShape(SUNMatrix a, SUNMatrix b) {
  return SUNMatGetID(a) == SUNMATRIX_DENSE && SUNMatGetID(b) == SUNMATRIX_DENSE &&
         SM_ROWS_D(a) == SM_ROWS_D(b) && SM_COLUMNS_D(a) == SM_COLUMNS_D(b);
}

int MatZero(SUNMatrix a) {
  double* d = SM_DATA_D(a);
  for (sunindextype k = 0, n = SM_LDATA_D(a); k < n; ++k) d[k] = 0.0;
  return SUNMAT_SUCCESS;
}

int MatCopy(SUNMatrix a, SUNMatrix b) {  // B = A
  if (!SameShape(a, b)) return SUNMAT_ILL_INPUT;
  const double* from = SM_DATA_D(a);
  double* to = SM_DATA_D(b);
  for (sunindextype k = 0, n = SM_LDATA_D(a); k < n; ++k) to[k] = from[k];
  return SUNMAT_SUCCESS;
}

int MatScaleAddI(double c, SUNMatrix a) {  // A = cA + I
  double* d = SM_DATA_D(a);
  for (sunindextype k = 0, n = SM_LDATA_D(a); k < n; ++k) d[k] *= c;
  const sunindextype rows = SM_ROWS_D(a), diagonal = std::min(rows, SM_COLUMNS_D(a));
  for (sunindextype j = 0; j < diagonal; ++j) d[j * rows + j] += 1.0;
  return SUNMAT_SUCCESS;
}

int MatScaleAdd(double c, SUNMatrix a, SUNMatrix b) {  // A = cA + B
  if (!SameShape(a, b)) return SUNMAT_ILL_INPUT;
  double* d = SM_DATA_D(a);
  const double* e = SM_DATA_D(b);
  for (sunindextype k = 0, n = SM_LDATA_D(a); k < n; ++k) d[k] = c * d[k] + e[k];
  return SUNMAT_SUCCESS;
}

SUNMatrix MatClone(SUNMatrix a) {
  SUNMatrix b = SUNDenseMatrix(SM_ROWS_D(a), SM_COLUMNS_D(a), a->sunctx);
  if (b) UseCompiledMatrixOps(b);
  return b;
}

}  // namespace

void UseCompiledMatrixOps(SUNMatrix a) {
  SUNMatrix_Ops ops = a->ops;
  ops->zero = MatZero;
  ops->copy = MatCopy;
  ops->scaleaddi = MatScaleAddI;
  ops->scaleadd = MatScaleAdd;
  ops->clone = MatClone;
}

void UseCompiledVectorOps(N_Vector v) {
  N_Vector_Ops ops = v->ops;
  ops->nvlinearsum = LinearSum;
  ops->nvscale = Scale;
  ops->nvconst = Const;
  ops->nvprod = Prod;
  ops->nvdiv = Div;
  ops->nvabs = Abs;
  ops->nvinv = Inv;
  ops->nvaddconst = AddConst;
  ops->nvcompare = Compare;
  ops->nvmaxnorm = MaxNorm;
  ops->nvmaxnormlocal = MaxNorm;
  ops->nvmin = Min;
  ops->nvminlocal = Min;
  ops->nvwsqrsumlocal = WSqrSum;
  ops->nvwrmsnorm = WrmsNorm;
  ops->nvlinearcombination = LinearCombination;
  ops->nvscaleaddmulti = ScaleAddMulti;
}

}  // namespace mechflow::blocks::sundials
