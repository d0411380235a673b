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
// The child dies with its parent (PR_SET_PDEATHSIG): a killed run leaves no case running.
ChildOutcome run_child(const std::vector<std::string>& args, double timeout_s, const std::function<bool()>& stop,
                       const std::function<void()>& waiting);

// A temporary folder for one isolated case, $TMPDIR/oitbench-case-PID-XXXXXX (PID: this process).
// Folders left by runs that were killed (their PID no longer exists, and they are ours) are removed
// first. Throws std::runtime_error when none can be made.
std::string make_case_dir();
// Removes every oitbench-case-PID-* folder in `tmp_dir` whose process is gone and that this user owns;
// returns how many. A folder of another naming, or of a living process, is left alone.
size_t remove_stale_case_dirs(const std::string& tmp_dir);

// A GPU call that does not return cannot be cancelled: when no heartbeat arrives for `timeout_s`
// seconds, the watchdog prints what was running and where the finished rows are, and ends the process.
// It also ends the process (exit 130) when a stop was requested (Ctrl-C, core/interrupt.hpp) and the
// run has not stopped kStopGraceSeconds later: a draw in flight cannot be cut short otherwise. With
// `heartbeat_lines`, it prints a line whenever no heartbeat came for kHeartbeatSeconds (a long warm-up
// or repetition), so a run never looks hung.
class Watchdog {
 public:
  static constexpr double kStopGraceSeconds = 3.0, kHeartbeatSeconds = 5.0;
  Watchdog(double timeout_s, std::string out, bool heartbeat_lines = false);
  Watchdog(const Watchdog&) = delete;
  Watchdog& operator=(const Watchdog&) = delete;
  ~Watchdog();
  void set_current(const std::string& what);  // and a heartbeat
  void heartbeat();

 private:
  void watch();
  double timeout_s_;
  std::string out_;
  bool heartbeat_lines_;
  std::mutex mutex_;
  std::condition_variable cv_;
  bool finished_ = false;
  std::string current_;
  std::chrono::steady_clock::time_point last_beat_ = std::chrono::steady_clock::now();
  std::thread thread_;
};

}  // namespace oitbench
