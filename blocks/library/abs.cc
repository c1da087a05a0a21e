#include "blocks/library/abs.h"

namespace mechflow::blocks {

AbsBlock::AbsBlock(const std::string& name, int width) : PiecewiseLinearBlock("abs", name, {0.0}, width) {}

}  // namespace mechflow::blocks
