#pragma once
// Stopping a long analysis when asked (Ctrl-C, SIGTERM): the caller passes
// the flag its signal handler sets (the command line's InterruptFlag()); the
// analysis looks at it between units of work (a transform, a run) and stops.
// analysis/ knows only the flag, not who sets it.

#include <csignal>
#include <stdexcept>
#include <string>

namespace mechflow::analysis {

// Non-zero (the signal's number) once the computation is to stop; null: never.
using CancelFlag = const volatile std::sig_atomic_t*;

// "SIGINT", "SIGTERM", "SIGHUP", else "signal N".
inline std::string SignalName(int signal) {
  switch (signal) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    case SIGHUP: return "SIGHUP";
    default: return "signal " + std::to_string(signal);
  }
}

// A computation stopped by a signal; nothing of it is kept.
class Interrupted : public std::runtime_error {
 public:
  explicit Interrupted(int signal) : std::runtime_error("interrupted by " + SignalName(signal)), signal_(signal) {}
  int signal() const { return signal_; }

 private:
  int signal_;
};

inline void StopIfInterrupted(CancelFlag flag) {
  if (flag && *flag) throw Interrupted(*flag);
}

}  // namespace mechflow::analysis
