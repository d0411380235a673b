#include "core/isolation.hpp"

#include <signal.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <stdexcept>

#include "core/interrupt.hpp"

namespace oitbench {

ChildOutcome run_child(const std::vector<std::string>& args, double timeout_s, const std::function<bool()>& stop,
                       const std::function<void()>& waiting) {
  std::vector<std::string> copy = args;
  std::vector<char*> argv;
  for (auto& a : copy) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t parent = getpid();
  pid_t pid = fork();
  if (pid == 0) {
    setpgid(0, 0);
    // Die with the parent; and if it died before prctl took effect, at once.
    if (prctl(PR_SET_PDEATHSIG, SIGKILL) != 0 || getppid() != parent) _exit(127);
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

namespace {
std::string temp_dir() {
  const char* t = std::getenv("TMPDIR");
  return t && *t ? t : "/tmp";
}
constexpr const char* kCaseDirPrefix = "oitbench-case-";
}  // namespace

size_t remove_stale_case_dirs(const std::string& tmp_dir) {
  namespace fs = std::filesystem;
  size_t removed = 0;
  std::error_code ec;
  for (fs::directory_iterator it(tmp_dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (!name.starts_with(kCaseDirPrefix)) continue;
    // oitbench-case-PID-XXXXXX: a process number, then mkdtemp's six characters.
    const std::string rest = name.substr(std::char_traits<char>::length(kCaseDirPrefix));
    const auto dash = rest.find('-');
    if (dash == std::string::npos || dash == 0 || dash > 10 || rest.size() != dash + 7) continue;
    if (rest.find_first_not_of("0123456789") != dash) continue;
    const long pid = std::stol(rest.substr(0, dash));
    struct stat st {};
    if (lstat(it->path().c_str(), &st) != 0 || !S_ISDIR(st.st_mode) || st.st_uid != getuid()) continue;
    if (pid <= 0 || pid == getpid() || kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;
    std::error_code rm;
    fs::remove_all(it->path(), rm);
    if (!rm) ++removed;
  }
  return removed;
}

std::string make_case_dir() {
  const std::string tmp = temp_dir();
  remove_stale_case_dirs(tmp);
  std::string tmpl = tmp + "/" + kCaseDirPrefix + std::to_string(getpid()) + "-XXXXXX";
  std::vector<char> buf(tmpl.begin(), tmpl.end());
  buf.push_back('\0');
  if (!mkdtemp(buf.data()))
    throw std::runtime_error("cannot create a temporary folder for an isolated case in " + tmp + ": " +
                             std::strerror(errno));
  return buf.data();
}

Watchdog::Watchdog(double timeout_s, std::string out, bool heartbeat_lines)
    : timeout_s_(timeout_s), out_(std::move(out)), heartbeat_lines_(heartbeat_lines) {
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
  using Clock = std::chrono::steady_clock;
  auto seconds_since = [](Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); };
  std::optional<Clock::time_point> stop_seen;
  Clock::time_point last_line = Clock::now();
  std::unique_lock lock(mutex_);
  while (!finished_) {
    cv_.wait_for(lock, std::chrono::milliseconds(200));
    if (finished_) break;
    if (stop_requested()) {
      if (!stop_seen) stop_seen = Clock::now();
      if (seconds_since(*stop_seen) > kStopGraceSeconds) {
        std::fprintf(stderr,
                     "\noitbench: interrupted; '%s' did not reach the end of a pass within %.0f s, so it is cut "
                     "short. Finished rows are in %s\n",
                     current_.c_str(), kStopGraceSeconds, out_.c_str());
        std::_Exit(130);
      }
      continue;
    }
    const double quiet = seconds_since(last_beat_);
    if (heartbeat_lines_ && quiet >= kHeartbeatSeconds && seconds_since(last_line) >= kHeartbeatSeconds) {
      std::fprintf(stderr, "\noitbench: still running '%s': %.0f s since the last repetition ended\n", current_.c_str(),
                   quiet);
      std::fflush(stderr);
      last_line = Clock::now();
    }
    if (quiet > timeout_s_) {
      std::fprintf(stderr,
                   "\noitbench: watchdog: '%s' made no progress for %.0f s (--timeout); stopping. "
                   "Finished rows are in %s; hang-prone experiments run isolated (--isolate always).\n",
                   current_.c_str(), timeout_s_, out_.c_str());
      std::_Exit(1);
    }
  }
}

}  // namespace oitbench
