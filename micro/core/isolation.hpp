#pragma once
// Keeping a run alive and honest when a case hangs: a case in a child process under a deadline,
// and the in-process watchdog that ends a run whose GPU call never returns.
#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace oitbench {

struct ChildOutcome {
  enum class Kind { Exited, Signalled, TimedOut, Stopped } kind = Kind::Exited;
  int code = 0;  // exit code (Exited) or signal number (Signalled)
};

// Runs `args` (args[0] is the executable) in a process group of its own, polling every 20 ms and
// calling `waiting` meanwhile; kills the group after `timeout_s` seconds or once `stop()` is true.
ChildOutcome run_child(const std::vector<std::string>& args, double timeout_s, const std::function<bool()>& stop,
                       const std::function<void()>& waiting);

// A GPU call that does not return cannot be cancelled: when no heartbeat arrives for `timeout_s`
// seconds, the watchdog prints what was running and where the finished rows are, and ends the process.
class Watchdog {
 public:
  Watchdog(double timeout_s, std::string out);
  Watchdog(const Watchdog&) = delete;
  Watchdog& operator=(const Watchdog&) = delete;
  ~Watchdog();
  void set_current(const std::string& what);  // and a heartbeat
  void heartbeat();

 private:
  void watch();
  double timeout_s_;
  std::string out_;
  std::mutex mutex_;
  std::condition_variable cv_;
  bool finished_ = false;
  std::string current_;
  std::chrono::steady_clock::time_point last_beat_ = std::chrono::steady_clock::now();
  std::thread thread_;
};

}  // namespace oitbench
