#include "blocks/library/held_input.h"

namespace mechflow::blocks {

HeldInputBlock::HeldInputBlock(const std::string& name, double start) : Block("input", name), start_(start) {
  DeclareOutputPort("y");
  DeclareDiscreteStates(1);
}

}  // namespace mechflow::blocks
