#include "core/isolation.hpp"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>

namespace oitbench {

ChildOutcome run_child(const std::vector<std::string>& args, double timeout_s, const std::function<bool()>& stop,
                       const std::function<void()>& waiting) {
  std::vector<std::string> copy = args;
  std::vector<char*> argv;
  for (auto& a : copy) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = fork();
  if (pid == 0) {
    setpgid(0, 0);
    execv(argv[0], argv.data());
    _exit(127);
  }
  auto t0 = std::chrono::steady_clock::now();
  int status = 0;
  for (;;) {
    if (waitpid(pid, &status, WNOHANG) == pid) break;
    double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    bool stopped = stop();
    if (stopped || elapsed > timeout_s) {
      kill(-pid, SIGKILL);
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      return {stopped ? ChildOutcome::Kind::Stopped : ChildOutcome::Kind::TimedOut, 0};
    }
    waiting();
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (WIFSIGNALED(status)) return {ChildOutcome::Kind::Signalled, WTERMSIG(status)};
  return {ChildOutcome::Kind::Exited, WEXITSTATUS(status)};
}

Watchdog::Watchdog(double timeout_s, std::string out) : timeout_s_(timeout_s), out_(std::move(out)) {
  thread_ = std::thread([this] { watch(); });
}

Watchdog::~Watchdog() {
  {
    std::lock_guard lock(mutex_);
    finished_ = true;
  }
  cv_.notify_all();
  thread_.join();
}

void Watchdog::set_current(const std::string& what) {
  std::lock_guard lock(mutex_);
  current_ = what;
  last_beat_ = std::chrono::steady_clock::now();
}

void Watchdog::heartbeat() {
  std::lock_guard lock(mutex_);
  last_beat_ = std::chrono::steady_clock::now();
}

void Watchdog::watch() {
  std::unique_lock lock(mutex_);
  while (!finished_) {
    cv_.wait_for(lock, std::chrono::milliseconds(200));
    if (finished_) break;
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - last_beat_).count() > timeout_s_) {
      std::fprintf(stderr,
                   "\noitbench: watchdog: '%s' made no progress for %.0f s (--timeout); stopping. "
                   "Finished rows are in %s; hang-prone experiments run isolated (--isolate always).\n",
                   current_.c_str(), timeout_s_, out_.c_str());
      std::_Exit(1);
    }
  }
}

}  // namespace oitbench
