#pragma once
// The two kinds of failure a user can cause, shared by every layer.
//
// InputError: the diagram, model or script is wrong (exit code 2). The message
// already names where (file:line, block.port, identifier) and what was expected.
// SimulationError: the input was accepted but the run could not be completed
// (exit code 1); results computed so far are kept by the caller.

#include <stdexcept>
#include <string>

namespace mechflow {

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class SimulationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace mechflow
