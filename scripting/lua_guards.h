#pragma once
// Guards on the few standard Lua functions whose work the instruction count
// cannot see, and on the metatables the straight-line fast path relies on.
//
// The instruction count (LuaState) bounds Lua code, but a C function runs as
// one instruction, and a finalizer runs with hooks off. So, in every state:
//   - string.rep returns an empty result at once (Lua's own loops n times
//     even when it copies nothing: string.rep('', 2^53));
//   - table.move refuses to move more elements than a table can hold under
//     the memory limit (moving nils allocates nothing, so the memory limit
//     would not stop it);
//   - string.find, match, gmatch and gsub refuse a pattern whose backtracking
//     over the subject could exceed kPatternStepBudget steps: a pattern with
//     k repetition items (*, +, -) and j optional ones (?) on n bytes may
//     take about n^(k+1) 2^j steps (n^k 2^j when anchored with ^). Plain
//     finds and patterns without repetitions are linear and always allowed;
//   - xpcall skips the script's message handler for a limit's error (raised
//     inside a hook, where the handler would run with hooks off);
//   - setmetatable refuses a metatable with __gc: finalizers run outside any
//     call mechflow can bound (Lua turns hooks off for them);
//   - the string metatable and _G's metatable are protected (__metatable),
//     so a script can neither point string arithmetic or indexing at Lua
//     code nor give _G an __index that straight-line code would run.
// The unsafe debug library (--unsafe-lua) can still get around these, by
// the user's choice.

#include <cstddef>

struct lua_State;

namespace mechflow::scripting {

// Steps of pattern matching one call may need at most (about a second).
inline constexpr double kPatternStepBudget = 2e8;

// Installs the guards; runs in protected mode during the state's set-up,
// after the standard libraries are open.
void InstallLuaGuards(lua_State* L, std::size_t memory_limit);

}  // namespace mechflow::scripting
