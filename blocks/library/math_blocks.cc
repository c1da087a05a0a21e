#include "blocks/library/math_blocks.h"

#include "mech/errors.h"

namespace mechflow::blocks {
namespace {

std::string InputName(int i, int n) { return n == 1 ? "u" : "u" + std::to_string(i + 1); }

}  // namespace

GainBlock::GainBlock(const std::string& name, double k, int width) : Block("gain", name), k_(k) {
  DeclareInputPort("u", width);
  DeclareOutputPort("y", width);
}

void GainBlock::DoCalcOutput(int, const BlockContext& ctx) const {
  const auto u = ctx.input(0);
  const auto y = ctx.output(0);
  for (size_t i = 0; i < y.size(); ++i) y[i] = k_ * u[i];
}

SumBlock::SumBlock(const std::string& name, const std::string& signs, int width) : Block("sum", name) {
  for (size_t i = 0; i < signs.size(); ++i) {
    DeclareInputPort(InputName(static_cast<int>(i), static_cast<int>(signs.size())), width);
    signs_.push_back(signs[i] == '-' ? -1.0 : 1.0);
  }
  DeclareOutputPort("y", width);
}

void SumBlock::DoCalcOutput(int, const BlockContext& ctx) const {
  const auto y = ctx.output(0);
  for (size_t j = 0; j < y.size(); ++j) y[j] = 0.0;
  for (int i = 0; i < num_inputs(); ++i) {
    const auto u = ctx.input(i);
    for (size_t j = 0; j < y.size(); ++j) y[j] += signs_[i] * u[j];
  }
}

ProductBlock::ProductBlock(const std::string& name, const std::string& operations, int width)
    : Block("product", name), operations_(operations) {
  for (size_t i = 0; i < operations.size(); ++i)
    DeclareInputPort(InputName(static_cast<int>(i), static_cast<int>(operations.size())), width);
  DeclareOutputPort("y", width);
}

void ProductBlock::DoCalcOutput(int, const BlockContext& ctx) const {
  const auto y = ctx.output(0);
  for (size_t j = 0; j < y.size(); ++j) y[j] = 1.0;
  for (int i = 0; i < num_inputs(); ++i) {
    const auto u = ctx.input(i);
    for (size_t j = 0; j < y.size(); ++j) {
      if (operations_[i] == '*') {
        y[j] *= u[j];
      } else {
        if (u[j] == 0.0)
          throw SimulationError("block '" + name() + "': division by zero (input " + input_port(i).name +
                                ") at t = " + std::to_string(ctx.time()));
        y[j] /= u[j];
      }
    }
  }
}

}  // namespace mechflow::blocks
