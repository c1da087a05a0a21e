#include "blocks/library/constant.h"

#include <algorithm>

namespace mechflow::blocks {

ConstantBlock::ConstantBlock(const std::string& name, std::vector<double> value)
    : Block("constant", name), value_(std::move(value)) {
  DeclareOutputPort("y", static_cast<int>(value_.size()));
}

void ConstantBlock::DoCalcOutput(int, const BlockContext& ctx) const {
  std::copy(value_.begin(), value_.end(), ctx.output(0).begin());
}

}  // namespace mechflow::blocks
