#pragma once
// The globals a Lua chunk reads that nothing defines: for `mechflow check`,
// which names them (a misspelt identifier in a control script reads nil and
// fails only when that line runs, perhaps an hour into a sweep).
//
// A scan of the chunk's tokens (scripting/lua_lexer.h), not a parser. A name
// read is a name token that is not a field (after '.' or ':'), a table key
// ('{ key = ...'), a label or goto target, or the target of an assignment.
// It is unknown when the chunk declares it nowhere (local, parameter, for
// variable, assignment or function statement -- anywhere in the chunk: the
// scan does not follow scopes, so it misses some and never invents one), it
// is not an identifier of the diagram (any case) and the sandbox's globals
// have no value of that name (math, string, sin, pi, ...; with
// --unsafe-lua, io and os too).

#include <string>
#include <vector>

namespace mechflow::scripting {

class IdentifierTable;
class LuaState;

struct GlobalRead {
  std::string name;
  int line = 0;  // of the first read, 1-based in `code`
};

// Every name `code` reads as a global and never declares, first reads first.
std::vector<GlobalRead> GlobalReads(const std::string& code);

// Those of them that are neither identifiers nor the sandbox's globals.
std::vector<GlobalRead> UnknownGlobals(const std::string& code, const IdentifierTable& identifiers,
                                       const LuaState& lua);

}  // namespace mechflow::scripting
