#include "cli/interrupt.h"

#include <atomic>

namespace mechflow::cli {
namespace {

volatile std::sig_atomic_t g_interrupt = 0;
volatile std::sig_atomic_t g_count = 0;
std::atomic<int> g_depth{0};  // InterruptHandlers alive

void OnInterrupt(int signal) {
  g_interrupt = signal;
  g_count = g_count + 1;
}

// Catches `signal` unless it is ignored (nohup, a background job), keeping
// the previous action in `old`.
void Catch(int signal, struct sigaction* old) {
  sigaction(signal, nullptr, old);
  if (old->sa_handler == SIG_IGN) return;
  struct sigaction action {};
  action.sa_handler = OnInterrupt;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  sigaction(signal, &action, nullptr);
}

}  // namespace

const volatile std::sig_atomic_t* InterruptFlag() { return &g_interrupt; }

int InterruptCount() { return g_count; }

InterruptHandlers::InterruptHandlers() : outermost_(g_depth++ == 0) {
  if (!outermost_) return;
  g_interrupt = 0;
  g_count = 0;
  Catch(SIGINT, &old_int_);
  Catch(SIGTERM, &old_term_);
  Catch(SIGHUP, &old_hup_);
}

InterruptHandlers::~InterruptHandlers() {
  --g_depth;
  if (!outermost_) return;
  sigaction(SIGINT, &old_int_, nullptr);
  sigaction(SIGTERM, &old_term_, nullptr);
  sigaction(SIGHUP, &old_hup_, nullptr);
}

}  // namespace mechflow::cli
