#include "cli/interrupt.h"

namespace mechflow::cli {
namespace {

volatile std::sig_atomic_t g_interrupt = 0;

void OnInterrupt(int signal) { g_interrupt = signal; }

}  // namespace

const volatile std::sig_atomic_t* InterruptFlag() { return &g_interrupt; }

InterruptHandlers::InterruptHandlers() {
  g_interrupt = 0;
  struct sigaction action {};
  action.sa_handler = OnInterrupt;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  sigaction(SIGINT, &action, &old_int_);
  sigaction(SIGTERM, &action, &old_term_);
}

InterruptHandlers::~InterruptHandlers() {
  sigaction(SIGINT, &old_int_, nullptr);
  sigaction(SIGTERM, &old_term_, nullptr);
}

}  // namespace mechflow::cli
