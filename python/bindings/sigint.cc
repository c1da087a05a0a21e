#include "python/bindings/bindings.h"

namespace mechflow::python {
namespace {

volatile std::sig_atomic_t g_interrupt = 0;

void OnSigint(int signal) { g_interrupt = signal; }

}  // namespace

SigintGuard::SigintGuard(bool install) {
  if (!install) return;
  sigaction(SIGINT, nullptr, &old_);
  if (old_.sa_handler == SIG_IGN) return;
  g_interrupt = 0;
  struct sigaction action {};
  action.sa_handler = OnSigint;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  sigaction(SIGINT, &action, nullptr);
  installed_ = true;
}

SigintGuard::~SigintGuard() {
  if (installed_) sigaction(SIGINT, &old_, nullptr);
}

const volatile std::sig_atomic_t* SigintGuard::flag() const { return installed_ ? &g_interrupt : nullptr; }

}  // namespace mechflow::python
