#pragma once
// The "expression" block: y = a Lua expression of its inputs and t.
//
//   inputs:  one scalar port per name in `inputs` (default "u"), each feeding y
//   output:  y (width 1)
//   params:  expr   the expression, e.g. "mu*(1 - y1^2)*y2 - y1"
//            inputs space-separated input names (may be empty: a function of t)
//
// Identifiers of the diagram may be used by name (case-insensitive); their
// values are taken when the diagram is loaded. The expression is compiled once
// (see CompiledExpression); a Lua error during the run fails the run with the
// block named.

#include "blocks/block_factory.h"

namespace mechflow::scripting {

class IdentifierTable;
class LuaState;

// Registers the Lua-based block types ("expression").
void RegisterScriptingBlocks(blocks::BlockRegistry* registry, LuaState* lua, const IdentifierTable* identifiers);

}  // namespace mechflow::scripting
