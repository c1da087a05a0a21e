#pragma once
// Elementwise arithmetic; every input feeds the output directly.
//
//   gain     u -> y = k u                                   (width w)
//   sum      u1..un -> y = s1 u1 + ... + sn un, s_i from `signs` ("+-+")
//   product  u1..un -> y = u1 op2 u2 ... , op_i from `operations` ("**/"):
//            '*' multiplies, '/' divides (a zero divisor fails the run)

#include <string>

#include "blocks/block.h"

namespace mechflow::blocks {

class GainBlock : public Block {
 public:
  GainBlock(const std::string& name, double k, int width);

 protected:
  void DoCalcOutput(int port, const BlockContext& ctx) const override;

 private:
  double k_;
};

class SumBlock : public Block {
 public:
  // `signs`: one '+' or '-' per input (checked by the factory).
  SumBlock(const std::string& name, const std::string& signs, int width);

 protected:
  void DoCalcOutput(int port, const BlockContext& ctx) const override;

 private:
  std::vector<double> signs_;
};

class ProductBlock : public Block {
 public:
  // `operations`: one '*' or '/' per input; the first applies to 1.
  ProductBlock(const std::string& name, const std::string& operations, int width);

 protected:
  void DoCalcOutput(int port, const BlockContext& ctx) const override;

 private:
  std::string operations_;
};

}  // namespace mechflow::blocks
