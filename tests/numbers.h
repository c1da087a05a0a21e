#pragma once
// Constants the tests share. Defined once here, not once per test file: the
// files of a test folder are compiled together (a unity build), where two
// definitions of one name in a file would clash.

#include <numbers>

namespace mechflow::testing {

inline constexpr double kPi = std::numbers::pi;

}  // namespace mechflow::testing
