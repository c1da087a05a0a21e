#include "blocks/library/product.h"

#include "blocks/library/port_names.h"
#include "mech/errors.h"

namespace mechflow::blocks {

ProductBlock::ProductBlock(const std::string& name, const std::string& operations, int width)
    : Block("product", name), operations_(operations) {
  const int n = static_cast<int>(operations.size());
  for (int i = 0; i < n; ++i) DeclareInputPort(NumberedInputName(i, n), width);
  DeclareOutputPort("y", width);
}

void ProductBlock::DoCalcOutput(int, const BlockContext& ctx) const {
  const auto y = ctx.output(0);
  for (double& v : y) v = 1.0;
  for (int i = 0; i < num_inputs(); ++i) {
    const auto u = ctx.input(i);
    if (operations_[i] == '*') {
      for (size_t j = 0; j < y.size(); ++j) y[j] *= u[j];
      continue;
    }
    for (size_t j = 0; j < y.size(); ++j) {
      // the message is built only on this failing path
      if (u[j] == 0.0)
        throw SimulationError("block '" + name() + "': division by zero (input " + input_port(i).name +
                              (y.size() > 1 ? "[" + std::to_string(j) + "]" : "") +
                              " is 0) at t = " + std::to_string(ctx.time()));
      y[j] /= u[j];
    }
  }
}

}  // namespace mechflow::blocks
