#pragma once
// Ctrl-C, SIGTERM and SIGHUP (a closed terminal) during a command: while an
// InterruptHandlers lives, the signals only set a flag (to the signal's
// number) and count, which the simulator reads before every output row
// (blocks::Simulator::SetInterruptFlag): the run ends at its last complete
// row, and what it computed is written as for any other end. Further signals
// only set the flag again, so they cannot cut the files short; a program
// mechflow waits for (gnuplot: cli/plot.h) is stopped by them.
//
// A signal ignored when the handlers are installed (nohup ignores SIGHUP, a
// shell's background job SIGINT) stays ignored.

#include <csignal>
#include <stdexcept>
#include <string>

#include "analysis/interrupted.h"

namespace mechflow::cli {

// The flag; 0 while no signal came.
const volatile std::sig_atomic_t* InterruptFlag();

// How many signals came since the outermost InterruptHandlers was made: a
// wait that starts after the run ended can tell a new signal from the one
// that ended the run.
int InterruptCount();

using analysis::SignalName;  // "SIGINT", "SIGTERM", "SIGHUP"

// A command cut short by a signal after its run: `signal` gives the exit
// code (128 + signal, as shells report it).
class Interrupted : public std::runtime_error {
 public:
  Interrupted(int signal, const std::string& what) : std::runtime_error(what), signal_(signal) {}
  int signal() const { return signal_; }

 private:
  int signal_;
};

// The handlers for the life of one command; the previous ones come back
// after. They nest: an inner one (around a wait for gnuplot) keeps the
// outer one's flag and count.
class InterruptHandlers {
 public:
  InterruptHandlers();
  ~InterruptHandlers();
  InterruptHandlers(const InterruptHandlers&) = delete;
  InterruptHandlers& operator=(const InterruptHandlers&) = delete;

 private:
  bool outermost_ = false;
  struct sigaction old_int_ {}, old_term_ {}, old_hup_ {};
};

}  // namespace mechflow::cli
