#pragma once
// The "expression" block: y = a Lua expression of its inputs and t.
//
//            +------------+
//   u1  ---> |            |
//   ...      | expression | ---> y
//   un  ---> |            |
//            +------------+
//
//   inputs:  one scalar port per name in `inputs` (default "u"), each feeding
//            y directly; none when `inputs` is empty (a function of t only)
//   output:  y (width 1)
//   params:  expr    (text, required) the expression, e.g. "mu*(1 - y1^2)*y2 - y1"
//            inputs  (text, default "u") space-separated input names, each a
//                    Lua name other than t and not an identifier's name
//
// Identifiers of the diagram may be used by name (case-insensitive); their
// values are taken when the diagram is loaded. The expression is compiled once
// (CompiledExpression, chunk "=block '<name>'"); a Lua error during the run, or
// a result that is not a finite number, fails the step with SimulationError
// naming the block, the time and the inputs.

#include "blocks/framework/block_factory.h"

namespace mechflow::scripting {

class IdentifierTable;
class LuaState;

// Registers the Lua-based block types ("expression"). `lua` and `identifiers`
// must outlive the registry and every block it creates; `identifiers` must be
// evaluated before blocks are created.
void RegisterScriptingBlocks(blocks::BlockRegistry* registry, LuaState* lua, const IdentifierTable* identifiers);

}  // namespace mechflow::scripting
