#include "tsp/core/interrupt.h"

#include <signal.h>

#include <csignal>
#include <string>

namespace tsp {

namespace {

// The signal that interrupted (0: none). Written only by the handler and the test hooks.
volatile std::sig_atomic_t g_signal = 0;
// A child to stop with SIGTERM on interruption (0: none).
volatile std::sig_atomic_t g_child = 0;
int g_depth = 0;  // nesting of InterruptScope (main thread only)
struct sigaction g_old_int {}, g_old_term {};

extern "C" void on_signal(int sig) {
  if (g_signal != 0) {  // the second signal: end now, by the signal, as without a handler
    ::signal(sig, SIG_DFL);
    ::raise(sig);
    return;
  }
  g_signal = sig;
  if (g_child > 0) ::kill(pid_t(g_child), SIGTERM);
}

}  // namespace

InterruptScope::InterruptScope() {
  if (g_depth++ > 0) return;
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;  // slow system calls resume; loops and commits check the flag
  ::sigaction(SIGINT, &sa, &g_old_int);
  ::sigaction(SIGTERM, &sa, &g_old_term);
}

InterruptScope::~InterruptScope() {
  if (--g_depth > 0) return;
  ::sigaction(SIGINT, &g_old_int, nullptr);
  ::sigaction(SIGTERM, &g_old_term, nullptr);
}

bool interrupted() { return g_signal != 0; }

void throw_if_interrupted() {
  const int sig = g_signal;
  if (sig == 0) return;
  throw Interrupted(std::string("interrupted by ") + (sig == SIGTERM ? "SIGTERM" : "SIGINT") +
                    "; temporaries removed, existing outputs left as they were");
}

StopChildOnInterrupt::StopChildOnInterrupt(pid_t pid) {
  g_child = std::sig_atomic_t(pid);
  if (g_signal != 0) ::kill(pid, SIGTERM);  // the signal came before the child was registered
}

StopChildOnInterrupt::~StopChildOnInterrupt() { g_child = 0; }

namespace detail {
void simulate_interrupt(int signal_number) { g_signal = signal_number; }
void clear_interrupt() { g_signal = 0; }
}  // namespace detail

}  // namespace tsp
