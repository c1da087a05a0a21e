#pragma once
// Mechanism loader: a <mechanism> element (diagrams/FORMAT.md, "Mechanisms")
// compiled into a MechanismBlock -- bodies, joints, force elements, inputs and
// sensors -- with every error naming file:line.

#include <memory>
#include <string>
#include <vector>

#include "blocks/framework/block.h"
#include "diagrams/description.h"
#include "diagrams/evaluator.h"

namespace mechflow::diagrams {

// Appends to `warnings` what the assembled initial state says the user should
// check ("file:line: warning: contact 'floor' starts ... inside its plane").
std::unique_ptr<blocks::Block> BuildMechanismBlock(const ElementDesc& mechanism, const Evaluator& eval,
                                                   std::vector<std::string>* warnings);

}  // namespace mechflow::diagrams
