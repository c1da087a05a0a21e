#pragma once
// One libFuzzer target: `MECHFLOW_FUZZ_TARGET(body)` defines
// LLVMFuzzerTestOneInput. Built with clang's -fsanitize=fuzzer it is a
// fuzzer (scripts/fuzz.sh); built without, replay_main.cc gives it a main
// that runs the files named on its command line, which is how CTest replays
// the regression inputs under tests/fuzz/regressions/.
//
// A target feeds its input through one entry point and accepts the errors a
// user can cause (InputError, SimulationError): anything else -- a crash, a
// sanitizer report, another exception, a hang past libFuzzer's -timeout --
// is a finding.

#include <cstddef>
#include <cstdint>
#include <string>

#include "mech/errors.h"

#define MECHFLOW_FUZZ_TARGET(body)                                              \
  extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) { \
    const std::string input(reinterpret_cast<const char*>(data), size);         \
    try {                                                                       \
      body(input);                                                              \
    } catch (const mechflow::InputError&) {                                     \
    } catch (const mechflow::SimulationError&) {                                \
    }                                                                           \
    return 0;                                                                   \
  }
