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
//
// A whole chunk (a control script) is given the same reads by
// IdentifiersAsUpvalues: its identifier names become locals of the chunk,
// set from the chunk's arguments, which every function of the chunk shares.

#include <string>
#include <vector>

struct lua_State;

namespace mechflow::scripting {

class IdentifierTable;

// A chunk that reads identifiers by name, rewritten to read them as upvalues.
struct IdentifierChunk {
  // Line 1 starts with the prologue
  //   local __mechflow_binder, ts <const>, ... = ...; __mechflow_binder[1] =
  //   function() return ts, ... end; __mechflow_binder = nil;
  // and goes on with the code, so every line keeps its number. Identifier
  // names (any case; not fields, table keys or labels) are lower-case.
  // Called with a table (the box) and one value per identifier, it stores in
  // box[1] a closure over every identifier: bind that one (BindIdentifiers).
  std::string code;
  std::vector<std::string> identifiers;  // lower-case, each once, by first use
};

// `<const>`: the chunk cannot assign an identifier (Lua refuses to compile
// `Ts = 1` with "attempt to assign to const variable 'ts'"), so it cannot
// seem to change one without sim:set; a local of the same name still may.
IdentifierChunk IdentifiersAsUpvalues(const std::string& code, const IdentifierTable& identifiers);

// Registers the function at stack index `index` (unchanged on the stack).
void BindIdentifiers(lua_State* L, int index);

// Gives every registered function's upvalues named in `changed` (lower-case
// identifier names) their current value from `identifiers`. Returns how many
// upvalues were set.
int RebindIdentifiers(lua_State* L, const IdentifierTable& identifiers, const std::vector<std::string>& changed);

}  // namespace mechflow::scripting
