#pragma once
// The "lua" block: outputs (and derivatives of its own continuous states)
// computed by Lua functions the diagram defines.
//
//            +-----------------------------+
//   u1  ---> |  outputs(t, x..., u...)     | ---> y1
//   ...      |  derivatives(t, x..., u...) | ---> ...
//   un  ---> |  (states x1 ... xm)         | ---> yk
//            +-----------------------------+
//
//   params:  inputs       (text, default "") input ports "u v:3" (a name,
//                         optionally ":width"); none by default
//            outputs      (text, default "y") output ports, same syntax
//            states       (text, default "") continuous state names
//            initial      (numbers, default all 0) one per state
//            feedthrough  (text, default: every output reads every input)
//                         "y:u,v z:w" lists, for each output that reads
//                         inputs at the same instant, the inputs it reads;
//                         outputs not listed read none; "none": no output
//                         reads an input
//            src          (path) a Lua file with the code, or else the
//                         element's text is the code
//
// The code runs once, at load, in an environment of its own (globals it
// defines stay in the block; reads fall through to the sandbox's globals). It
// must define `derivatives` exactly when the block has states, and `outputs`
// unless the outputs are the states: a block with states and no `outputs`
// copies its states to its outputs (their values must number the states; no
// feedthrough), which saves one Lua call per evaluation.
// Both are called with the time t [s], every state, then every input value
// (a port of width w gives w consecutive arguments), and return every output
// value in port order (`derivatives`: one value per state), finite numbers.
//
// Compiled once, as CompiledExpression does: identifiers the code names
// (case-insensitive) and the sandbox's expression functions it uses become
// upvalues set before the code runs,
//   local mass, k, sin = <mass>, <k>, <sin>; <the code>
// all on line 1, so messages point at the code's own lines (inline code gets
// the XML file as chunk name and is shifted to its line in the file). One
// closure capturing every identifier upvalue is registered with
// BindIdentifiers; Lua's closures share captured locals, so a control script
// changing an identifier changes it for every function of the code.
//
// At run time a call pushes numbers and reads numbers: no parsing, no name
// look-up, no allocation in C++. Every call is bounded by the LuaState's
// instruction limit, except straight-line code that cannot loop (see
// CodeScan in lua_block.cc), as CompiledExpression does. Errors (a Lua
// error, a wrong number of values, a value that is not a finite number)
// throw SimulationError naming the block, the function, the time, the Lua
// line and a traceback.
//
// A block with several output ports computes them in one call: `outputs` is
// called again for a port only when time, states or inputs differ from the
// call that filled the others (ports of different feedthrough are scheduled
// apart, and an algebraic loop re-evaluates with new inputs).

#include "blocks/framework/block_factory.h"

namespace mechflow::scripting {

class IdentifierTable;
class LuaState;

// Registers the "lua" block type. `lua` and `identifiers` must outlive the
// registry and every block it creates; identifiers must be evaluated first.
// The type takes the element's text (BlockType::takes_text): the loader
// passes it as texts "#text" and "#text_file" and number "#text_line" (the
// file line of the text's first character).
void RegisterLuaBlock(blocks::BlockRegistry* registry, LuaState* lua, const IdentifierTable* identifiers);

}  // namespace mechflow::scripting
