// The compiled operations (blocks/solver/compiled_ops.h) give NVECTOR_SERIAL's and
// SUNMATRIX_DENSE's numbers bit for bit: every special case of the vector
// coefficients, every way an output may alias an input, the fused vector
// operations against the linear sums SUNDIALS performs without them, and the
// Newton matrix's copy and scaling.

#include "blocks/solver/compiled_ops.h"

#include <cstring>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "blocks/solver/sundials.h"

namespace mechflow::blocks::sundials {
namespace {

constexpr sunindextype kN = 37;  // odd: no loop may assume pairs

// Two sets of the same vectors: one with SUNDIALS's operations, one with ours.
class VectorOpsTest : public ::testing::Test {
 protected:
  VectorOpsTest() {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> value(-3.0, 3.0);
    for (int k = 0; k < kVectors; ++k) {
      std::vector<double> v(kN);
      for (double& x : v) x = value(rng);
      v[3] = 0.0;
      v[5] = 1e-300 * value(rng);
      v[8] = 1e20 * value(rng);
      for (N_Vector* set : {stock_, ours_}) {
        set[k] = N_VNew_Serial(kN, ctx_.get());
        std::memcpy(N_VGetArrayPointer(set[k]), v.data(), kN * sizeof(double));
      }
      UseCompiledVectorOps(ours_[k]);
    }
    // positive weights for the norms
    for (N_Vector* set : {stock_, ours_})
      for (sunindextype i = 0; i < kN; ++i) N_VGetArrayPointer(set[kWeights])[i] = 0.5 + i;
  }
  ~VectorOpsTest() override {
    for (int k = 0; k < kVectors; ++k) N_VDestroy(stock_[k]), N_VDestroy(ours_[k]);
  }
  void ExpectSame(const char* what) const {
    for (int k = 0; k < kVectors; ++k)
      ASSERT_EQ(std::memcmp(N_VGetArrayPointer(stock_[k]), N_VGetArrayPointer(ours_[k]), kN * sizeof(double)), 0)
          << what << ": vector " << k;
  }

  static constexpr int kVectors = 9, kWeights = 8;
  Context ctx_;
  N_Vector stock_[kVectors], ours_[kVectors];
};

const double kCoefficients[] = {1.0, -1.0, 0.0, 0.5, -0.5, 0.3, -0.3, 2.0};

TEST_F(VectorOpsTest, LinearSumInEveryCaseAndAliasing) {
  for (const double a : kCoefficients)
    for (const double b : kCoefficients)
      for (const int z : {2, 0, 1}) {  // apart, z = x, z = y
        N_VLinearSum(a, stock_[0], b, stock_[1], stock_[z]);
        N_VLinearSum(a, ours_[0], b, ours_[1], ours_[z]);
        ExpectSame(("linear sum a = " + std::to_string(a) + ", b = " + std::to_string(b) + ", z " +
                    std::to_string(z)).c_str());
      }
}

TEST_F(VectorOpsTest, ElementwiseOperations) {
  for (const double c : kCoefficients)
    for (const int z : {2, 0}) {
      N_VScale(c, stock_[0], stock_[z]);
      N_VScale(c, ours_[0], ours_[z]);
      ExpectSame("scale");
    }
  for (N_Vector* v : {stock_, ours_}) {
    N_VProd(v[0], v[1], v[2]);
    N_VDiv(v[2], v[3], v[4]);
    N_VAbs(v[4], v[5]);
    N_VInv(v[5], v[6]);
    N_VAddConst(v[6], 0.7, v[6]);
    N_VCompare(1.5, v[1], v[7]);
    N_VConst(0.25, v[3]);
  }
  ExpectSame("elementwise");
}

TEST_F(VectorOpsTest, Reductions) {
  for (int k = 0; k < kVectors; ++k) {
    EXPECT_EQ(N_VWrmsNorm(stock_[k], stock_[kWeights]), N_VWrmsNorm(ours_[k], ours_[kWeights])) << k;
    EXPECT_EQ(N_VWSqrSumLocal(stock_[k], stock_[kWeights]), N_VWSqrSumLocal(ours_[k], ours_[kWeights])) << k;
    EXPECT_EQ(N_VMaxNorm(stock_[k]), N_VMaxNorm(ours_[k])) << k;
    EXPECT_EQ(N_VMin(stock_[k]), N_VMin(ours_[k])) << k;
  }
  N_VConst(0.0, stock_[0]);
  N_VConst(0.0, ours_[0]);
  EXPECT_EQ(N_VWrmsNorm(ours_[0], ours_[kWeights]), 0.0);
}

// SUNDIALS's own vectors have no fused operations: it scales and adds.
TEST_F(VectorOpsTest, LinearCombinationAsScaleThenSums) {
  double c[] = {0.3, -1.0, 1.0, 2.5, -0.7, 0.5};
  for (int nvec = 1; nvec <= 6; ++nvec)
    for (const int z : {7, 0, 2}) {  // apart, z = X_0, z = X_2 (read after it is overwritten)
      if (z == 2 && nvec < 3) continue;
      N_Vector xs[6], xo[6];
      for (int k = 0; k < nvec; ++k) xs[k] = stock_[k], xo[k] = ours_[k];
      ASSERT_EQ(N_VLinearCombination(nvec, c, xs, stock_[z]), 0);
      ASSERT_EQ(N_VLinearCombination(nvec, c, xo, ours_[z]), 0);
      ExpectSame(("linear combination of " + std::to_string(nvec) + ", z " + std::to_string(z)).c_str());
    }
}

TEST_F(VectorOpsTest, ScaleAddMultiAsLinearSums) {
  double a[] = {1.0, -0.4, -1.0, 0.9};
  for (const int mode : {0, 1, 2}) {  // Z = Y, Z apart, Z_0 = x (changes x for Z_1, Z_2, Z_3)
    N_Vector ys[4], yo[4], zs[4], zo[4];
    for (int k = 0; k < 4; ++k) {
      ys[k] = stock_[1 + k], yo[k] = ours_[1 + k];
      zs[k] = mode == 0 ? ys[k] : stock_[5 + k % 3], zo[k] = mode == 0 ? yo[k] : ours_[5 + k % 3];
    }
    if (mode == 2) zs[0] = stock_[0], zo[0] = ours_[0];
    ASSERT_EQ(N_VScaleAddMulti(4, a, stock_[0], ys, zs), 0);
    ASSERT_EQ(N_VScaleAddMulti(4, a, ours_[0], yo, zo), 0);
    ExpectSame(("scale-add-multi, mode " + std::to_string(mode)).c_str());
  }
}

TEST_F(VectorOpsTest, ClonesInheritTheOperations) {
  N_Vector clone = N_VClone(ours_[0]);
  EXPECT_EQ(clone->ops->nvlinearsum, ours_[0]->ops->nvlinearsum);
  EXPECT_NE(clone->ops->nvlinearsum, stock_[0]->ops->nvlinearsum);
  N_VDestroy(clone);
}

// A stock and a compiled 5 x 5 matrix (and a 5 x 3 one) with the same random entries.
TEST(CompiledMatrixOpsTest, CopyScaleAndCloneAsSundials) {
  Context ctx;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> value(-2.0, 2.0);
  SUNMatrix stock[3], ours[3];
  const sunindextype rows[3] = {5, 5, 5}, columns[3] = {5, 5, 3};
  for (int k = 0; k < 3; ++k) {
    stock[k] = SUNDenseMatrix(rows[k], columns[k], ctx.get());
    ours[k] = SUNDenseMatrix(rows[k], columns[k], ctx.get());
    UseCompiledMatrixOps(ours[k]);
    for (sunindextype i = 0; i < rows[k] * columns[k]; ++i)
      SUNDenseMatrix_Data(stock[k])[i] = SUNDenseMatrix_Data(ours[k])[i] = value(rng);
  }
  auto expect_same = [&](const char* what) {
    for (int k = 0; k < 3; ++k)
      ASSERT_EQ(std::memcmp(SUNDenseMatrix_Data(stock[k]), SUNDenseMatrix_Data(ours[k]),
                            rows[k] * columns[k] * sizeof(double)),
                0)
          << what << ": matrix " << k;
  };
  for (const double c : {-0.37, 1.0, -1.0, 2.5}) {
    ASSERT_EQ(SUNMatScaleAddI(c, stock[0]), SUNMatScaleAddI(c, ours[0]));
    expect_same("A = cA + I");
    ASSERT_EQ(SUNMatScaleAdd(c, stock[1], stock[0]), SUNMatScaleAdd(c, ours[1], ours[0]));
    expect_same("A = cA + B");
  }
  ASSERT_EQ(SUNMatScaleAddI(0.3, stock[2]), SUNMatScaleAddI(0.3, ours[2]));  // 5 x 3: I on the top square
  expect_same("A = cA + I, not square");
  EXPECT_EQ(SUNMatCopy(ours[0], ours[2]), SUNMAT_ILL_INPUT);  // shapes differ
  ASSERT_EQ(SUNMatCopy(stock[0], stock[1]), SUNMatCopy(ours[0], ours[1]));
  expect_same("copy");
  SUNMatrix clone = SUNMatClone(ours[1]);
  EXPECT_EQ(clone->ops->copy, ours[1]->ops->copy);
  EXPECT_NE(clone->ops->copy, stock[1]->ops->copy);
  SUNMatDestroy(clone);
  ASSERT_EQ(SUNMatZero(stock[1]), SUNMatZero(ours[1]));
  expect_same("zero");
  for (int k = 0; k < 3; ++k) SUNMatDestroy(stock[k]), SUNMatDestroy(ours[k]);
}

}  // namespace
}  // namespace mechflow::blocks::sundials
