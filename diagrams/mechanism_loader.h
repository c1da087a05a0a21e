#pragma once
// Mechanism loader: a <mechanism> element (diagrams/FORMAT.md, "Mechanisms")
// compiled into a MechanismBlock -- bodies, joints, force elements, inputs and
// sensors -- with every error naming file:line.

#include <memory>

#include "blocks/block.h"
#include "diagrams/description.h"
#include "diagrams/evaluator.h"

namespace mechflow::diagrams {

std::unique_ptr<blocks::Block> BuildMechanismBlock(const ElementDesc& mechanism, const Evaluator& eval);

}  // namespace mechflow::diagrams
