#include "core/interrupt.hpp"

#include <signal.h>
#include <unistd.h>

#include <csignal>

namespace oitbench {

namespace {

// The one piece of process-wide state: the signal that asked the run to stop (0: none).
volatile std::sig_atomic_t g_stop_signal = 0;

extern "C" void on_stop_signal(int sig) {
  if (g_stop_signal != 0) {  // the second Ctrl-C: at once, without unwinding (async-signal-safe calls only)
    static const char msg[] = "\noitbench: interrupted again; exiting now (every row already written is whole)\n";
    ssize_t n = write(STDERR_FILENO, msg, sizeof msg - 1);
    (void)n;
    _exit(130);
  }
  g_stop_signal = sig;
}

}  // namespace

SignalGuard::SignalGuard() {
  struct sigaction sa {};
  sa.sa_handler = on_stop_signal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, &old_int_);
  sigaction(SIGTERM, &sa, &old_term_);
}

SignalGuard::~SignalGuard() {
  sigaction(SIGINT, &old_int_, nullptr);
  sigaction(SIGTERM, &old_term_, nullptr);
}

bool SignalGuard::stopped() const { return stop_requested(); }

bool stop_requested() { return g_stop_signal != 0; }

void throw_if_stop_requested() {
  if (stop_requested()) throw Interrupted();
}

void request_stop_for_test(int sig) { g_stop_signal = sig; }

}  // namespace oitbench
