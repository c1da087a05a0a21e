#pragma once
// Port names shared by the blocks with a variable number of inputs.

#include <string>

namespace mechflow::blocks {

// Input port i (from 0) of n: "u" when n = 1, else "u1".."un".
inline std::string NumberedInputName(int i, int n) { return n == 1 ? "u" : "u" + std::to_string(i + 1); }

}  // namespace mechflow::blocks
