#pragma once
// Guards on the standard Lua functions whose work the instruction count
// cannot see, and on the metatables the straight-line fast path relies on.
//
// The instruction count (LuaState) bounds Lua code, but a C function runs as
// one instruction, and a finalizer runs with hooks off. So every function of
// the sandbox either does work bounded by what its arguments allocate (which
// the memory limit bounds: len, sub, upper, lower, reverse, byte, char,
// format (widths have at most 2 digits), pack, unpack, tostring, tonumber,
// select, rawlen, rawequal, next, pairs, ipairs, table.unpack and utf8.* --
// the values a call returns are bounded by Lua's stack), runs Lua code only
// through calls the count sees (pcall, a sort comparator, a gsub function,
// a metamethod), or is guarded here, in every state:
//   - string.rep returns an empty result at once (Lua's own loops n times
//     even when it copies nothing: string.rep('', 2^53));
//   - table.move refuses to move more elements than a table can hold under
//     the memory limit (moving nils allocates nothing, so the memory limit
//     would not stop it); table.insert and table.remove with a position,
//     table.sort and table.concat refuse a length beyond that limit (only a
//     __len can claim one: they would loop in C over nils, sort for hours
//     with a C comparator such as pcall), and so does table.concat for an
//     explicit range;
//   - string.find, match, gmatch and gsub refuse a pattern whose matching
//     could take more than kPatternStepBudget steps: a pattern of m bytes
//     with k repetition items (*, +, -, %b, back-references %1-%9) and j
//     optional ones (?) on n bytes may take about n^(k+1) 2^j m steps
//     (n^k 2^j m when anchored with ^, except in gmatch);
//   - a plain string.find (the 4th argument, or a pattern without special
//     characters) searches in time linear in n + m when Lua's own search
//     could take more than kPatternStepBudget steps (it takes up to n m);
//   - load refuses a chunk whose compilation could take more than
//     kCompileStepBudget steps: Lua's compiler takes time quadratic in the
//     number of 'and'/'or' of an expression, of 'elseif' of an if, and of
//     gotos, breaks and labels of a function (40000 'and' in a row: 2.7 s,
//     one million: half an hour). A chunk read by a function is read whole
//     first. mechflow applies the same check to the scripts, Lua blocks and
//     expressions of a diagram before compiling them (CompileCostProblem);
//   - collectgarbage, and the guarded functions above on subjects of 64 KiB
//     or more, look at the clock when done (their work grows with the heap
//     or the subject), so a loop of them stops at the time limit;
//   - xpcall skips the script's message handler for a limit's error (raised
//     inside a hook, where the handler would run with hooks off);
//   - setmetatable refuses a metatable with __gc: finalizers run outside any
//     call mechflow can bound (Lua turns hooks off for them);
//   - the string metatable and _G's metatable are protected (__metatable),
//     so a script can neither point string arithmetic or indexing at Lua
//     code nor give _G an __index that straight-line code would run.
// A refusal is raised as a limit's error (LuaState::RaiseLimit): pcall cannot
// catch it and carry on. Linear work is not free either: a loop of calls on
// long strings that allocate nothing (comparing, utf8.len, a plain find)
// meets the time limit only every LuaState::kCheckInterval instructions.
// Straight-line code runs without the count (CompiledExpression, the lua
// block): it is kept from values whose metatables could run Lua code (see
// there; LuaState::IsPureFunction, StraightLineCall).
// The unsafe debug library (--unsafe-lua) can still get around these, by
// the user's choice.

#include <cstddef>
#include <string>
#include <string_view>

struct lua_State;

namespace mechflow::scripting {

// Steps of pattern matching one call may need at most (about a second).
inline constexpr double kPatternStepBudget = 2e8;

// Steps of Lua's compiler one chunk may need at most (about 0.7 s): the sum
// of the halved squares of its numbers of 'and'/'or', of 'elseif' and of
// goto/break/labels, counted as whole words anywhere in the text.
inline constexpr double kCompileStepBudget = 2e8;

// Installs the guards; runs in protected mode during the state's set-up,
// after the standard libraries are open.
void InstallLuaGuards(lua_State* L, std::size_t memory_limit);

// Empty when Lua may compile `code` within kCompileStepBudget; else why not
// (to be prefixed by what the code is).
std::string CompileCostProblem(std::string_view code);

// The same for Lua's C functions: false when within the budget, else true
// with the reason in text[text_size]. Allocates nothing.
bool DescribeCompileCost(const char* code, std::size_t size, char* text, std::size_t text_size);

}  // namespace mechflow::scripting
