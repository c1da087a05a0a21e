#include "blocks/library/sum.h"

#include "blocks/library/port_names.h"

namespace mechflow::blocks {

SumBlock::SumBlock(const std::string& name, const std::string& signs, int width) : Block("sum", name) {
  const int n = static_cast<int>(signs.size());
  for (int i = 0; i < n; ++i) {
    DeclareInputPort(NumberedInputName(i, n), width);
    signs_.push_back(signs[i] == '-' ? -1.0 : 1.0);
  }
  DeclareOutputPort("y", width);
}

void SumBlock::DoCalcOutput(int, const BlockContext& ctx) const {
  const auto y = ctx.output(0);
  for (double& v : y) v = 0.0;
  for (int i = 0; i < num_inputs(); ++i) {
    const auto u = ctx.input(i);
    for (size_t j = 0; j < y.size(); ++j) y[j] += signs_[i] * u[j];
  }
}

}  // namespace mechflow::blocks
