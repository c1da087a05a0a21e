#pragma once
// Identifier bindings: Lua functions that read identifiers through upvalues.
//
// Compiled expressions and Lua blocks capture identifier values as upvalues
// (`local mass, c = ...` before the function), so evaluating them looks no
// name up. When a control script changes an identifier during a run, every
// such function must see the new value: each one is registered here, in a
// table of the Lua registry with weak keys (a function that is no longer
// referenced drops out by itself), and Rebind sets every upvalue named like
// a changed identifier.
//
// Upvalue names are the identifiers' canonical (lower-case) names, so a
// function registered here must use no other upvalue with such a name.

#include <string>
#include <vector>

struct lua_State;

namespace mechflow::scripting {

class IdentifierTable;

// Registers the function at stack index `index` (unchanged on the stack).
void BindIdentifiers(lua_State* L, int index);

// Gives every registered function's upvalues named in `changed` (lower-case
// identifier names) their current value from `identifiers`. Returns how many
// upvalues were set.
int RebindIdentifiers(lua_State* L, const IdentifierTable& identifiers, const std::vector<std::string>& changed);

}  // namespace mechflow::scripting
