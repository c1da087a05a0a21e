#pragma once
// Ctrl-C and SIGTERM during a run or a sweep: while an InterruptHandlers
// lives, the signals only set a flag (to the signal's number), which the
// simulator reads before every output row (blocks::Simulator::
// SetInterruptFlag): the run ends at its last complete row, and what it
// computed is written as for any other end. Further signals only set the
// flag again, so they cannot cut the files short.

#include <csignal>

namespace mechflow::cli {

// The flag; 0 while no signal came.
const volatile std::sig_atomic_t* InterruptFlag();

// The handlers for the life of one command; the previous ones come back after.
class InterruptHandlers {
 public:
  InterruptHandlers();
  ~InterruptHandlers();
  InterruptHandlers(const InterruptHandlers&) = delete;
  InterruptHandlers& operator=(const InterruptHandlers&) = delete;

 private:
  struct sigaction old_int_ {}, old_term_ {};
};

}  // namespace mechflow::cli
