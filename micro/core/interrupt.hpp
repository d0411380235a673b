#pragma once
// Ctrl-C and SIGTERM: the one piece of process-wide state (an async-signal-safe flag). A first signal
// asks the run to stop: the runner stops between cases, a case between its passes (PassTimer checks
// before each pass), and the watchdog's thread ends the process a few seconds later if a GPU call in
// flight does not return. A second signal ends the process at once (exit 130): every row already
// written is whole, since each row is one write().
#include <signal.h>

#include <stdexcept>

namespace oitbench {

// Thrown where work notices the stop request (before a pass): the case is not finished and writes no row.
class Interrupted : public std::runtime_error {
 public:
  Interrupted() : std::runtime_error("interrupted (Ctrl-C)") {}
};

// Installs the SIGINT/SIGTERM handlers for its lifetime (the runner holds one); restores the old ones.
class SignalGuard {
 public:
  SignalGuard();
  SignalGuard(const SignalGuard&) = delete;
  SignalGuard& operator=(const SignalGuard&) = delete;
  ~SignalGuard();
  bool stopped() const;

 private:
  struct sigaction old_int_ {
  }, old_term_{};
};

bool stop_requested();           // a stop signal arrived (false where no SignalGuard was ever installed)
void throw_if_stop_requested();  // throws Interrupted
// Tests: what a first signal does (sets the flag); 0 clears it.
void request_stop_for_test(int sig);

}  // namespace oitbench
