// Bad input and faults end to end, through the binary: every bad value of issue 16 a clear error with
// the same exit code in run, render and view; Ctrl-C within seconds of a long repetition (and a second
// Ctrl-C at once), with a heartbeat meanwhile; isolated cases that die with a killed parent and leave no
// folder behind for long; render naming only what it wrote; render targets past the driver's limits.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <functional>
#include <regex>
#include <sstream>
#include <thread>

#include "gl/render_target.hpp"
#include "support/test_support.hpp"

namespace oitbench::test {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// A message a user can read: no 309-digit bound (CLI11's NonNegativeNumber and PositiveNumber).
bool has_huge_number(const std::string& s) { return std::regex_search(s, std::regex("[0-9]{30}")); }

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void expect_usage_error(const std::vector<std::string>& args, const std::string& message) {
  auto r = run_oitbench(args, 120);
  std::string cmd;
  for (const auto& a : args) cmd += a + " ";
  EXPECT_EQ(r.exit_code, 2) << cmd << "\n" << r.err;
  EXPECT_TRUE(contains(r.err, message)) << cmd << "\nexpected: " << message << "\n" << r.err;
  EXPECT_FALSE(has_huge_number(r.err)) << cmd << "\n" << r.err;
  EXPECT_LT(r.err.size(), 2000u) << cmd << "\n" << r.err;
}

TEST(Faults, BadOptionValuesAreUsageErrorsNamingTheOption) {
  auto dir = temp_dir("bad-options");
  const std::string out = (dir / "x.csv").string();
  const std::vector<std::string> occ = {"run", "occupancy", "--quick", "--out", out};
  auto with = [&](std::vector<std::string> more) {
    auto a = occ;
    a.insert(a.end(), more.begin(), more.end());
    return a;
  };
  expect_usage_error(with({"--timeout", "nan"}), "--timeout");
  expect_usage_error(with({"--timeout", "0"}), "must be a number in (0, 604800] seconds");
  expect_usage_error(with({"--timeout", "inf"}), "must be a number in (0, 604800] seconds");
  expect_usage_error(with({"--device", "-1"}), "--device");
  expect_usage_error(with({"--device", "99"}), "--device 99 applies to --backend egl-device only");
  expect_usage_error({"frob"}, "unknown subcommand 'frob'");
  expect_usage_error(with({"--set", "size=1", "--set", "size=8"}), "--set size is given twice");
  expect_usage_error(with({"--resolution", "100000x100000"}), "each side must be in [1, 16384]");
  expect_usage_error(with({"--max-cases", "0"}), "--max-cases");
  expect_usage_error({"view", "--frames", "-1"}, "--frames");
  EXPECT_FALSE(fs::exists(out)) << "a refused run must not create its --out";
}

TEST(Faults, UnboundedRequestsAreRefusedBeforeAnythingIsBuilt) {
  auto dir = temp_dir("unbounded");
  const std::string out = (dir / "x.csv").string();
  auto t0 = Clock::now();
  expect_usage_error({"run", "occupancy", "--set", "seed=9223372036854775807..9223372036854775807", "--out", out},
                     "bad range");
  expect_usage_error(
      {"run", "occupancy", "--set", "size=1..1024", "--set", "draws=1..100000", "--set", "seed=1..1000", "--out", out},
      "more than 100000");
  EXPECT_LT(std::chrono::duration<double>(Clock::now() - t0).count(), 60.0);
  EXPECT_FALSE(fs::exists(out)) << "no header-only --out is left behind";
  // The cap can be lifted; then the run is sized by the user (here one case past the default is enough
  // to show the option works, without running them: --max-cases 1 refuses two).
  expect_usage_error({"run", "occupancy", "--quick", "--set", "size=1,2", "--max-cases", "1", "--out", out},
                     "more than 1;");
}

TEST(Faults, SpecialFilesAndFoldersAreRefusedByName) {
  auto dir = temp_dir("special");
  const std::string out = (dir / "x.csv").string();
  for (const char* dev : {"/dev/null", "/dev/full", "/dev/zero"})
    expect_usage_error({"run", "occupancy", "--quick", "--set", "size=1", "--out", dev},
                       std::string("--out ") + dev + ": is a character device, not a regular file");
  expect_usage_error({"run", "occupancy", "--quick", "--set", "size=1", "--out", dir.string() + "/"}, "names a folder");
  expect_usage_error({"run", "occupancy", "--quick", "--set", "size=1", "--out", dir.string()}, "is a folder");
  expect_usage_error({"run", "occupancy", "--quick", "--set", "size=1", "--out", out, "--raw", "/dev/full"},
                     "--raw /dev/full");
  expect_usage_error({"run", "occupancy", "--quick", "--set", "size=1", "--out", out, "--raw", out},
                     "--raw and --out name the same file");
  expect_usage_error({"run", "oit", "--quick", "--set", "scene=/dev/zero", "--out", out},
                     "/dev/zero: the scene file is a character device");
  expect_usage_error({"run", "--preset", "/dev/zero", "--out", out}, "/dev/zero: the preset is a character device");
  expect_usage_error({"run", "oit", "--quick", "--set", "scene=" + dir.string() + "/", "--out", out}, "is a folder");
  EXPECT_FALSE(fs::exists(out));
}

TEST(Faults, AMissingSceneOrViewIsTheSameUsageErrorInRunRenderAndView) {
  auto dir = temp_dir("missing-scene");
  expect_usage_error({"run", "oit", "--quick", "--set", "scene=nosuch", "--out", (dir / "a.csv").string()},
                     "scene 'nosuch'");
  expect_usage_error({"render", "--scene", "nosuch", "--out", (dir / "r.png").string()}, "scene 'nosuch'");
  expect_usage_error({"view", "--scene", "nosuch", "--frames", "1"}, "scene 'nosuch'");
  expect_usage_error({"run", "oit", "--quick", "--set", "view=nosuch", "--out", (dir / "b.csv").string()},
                     "has no view \"nosuch\"");
  expect_usage_error({"render", "--scene", "planes", "--view", "nosuch", "--out", (dir / "r.png").string()},
                     "has no view \"nosuch\"");
  expect_usage_error({"view", "--scene", "planes", "--view", "nosuch", "--frames", "1"}, "has no view \"nosuch\"");
}

TEST(Faults, RenderIntoAFolderIsRefusedAndWritesNoDotfiles) {
  auto dir = temp_dir("render-folder");
  expect_usage_error({"render", "--scene", "planes", "--out", dir.string() + "/"}, "names a folder");
  expect_usage_error({"render", "--scene", "planes", "--out", dir.string()}, "names a folder");
  EXPECT_TRUE(fs::is_empty(dir));
}

TEST(Faults, AFailedRenderNamesNoFileItDidNotWrite) {
  auto dir = temp_dir("render-failed");
  const auto png = dir / "old.png";
  std::ofstream(png) << "an image from an earlier render";
  auto r = run_oitbench({"render", "--scene", "planes", "--technique", "BASE-IS", "--resolution", "32x32", "--set",
                         "detail=small", "--set", "fault=compile-error", "--out", png.string()});
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_TRUE(contains(r.err, "no image written")) << r.err;
  EXPECT_FALSE(contains(r.err, "old.png,")) << r.err;
  EXPECT_FALSE(contains(r.err, png.string() + ",")) << r.err;
  EXPECT_TRUE(contains(r.err, "wrote " + (dir / "old.csv").string())) << r.err;  // its error row
  EXPECT_EQ(slurp(png), "an image from an earlier render");
}

// ---- Ctrl-C

// Starts oitbench with `env` added; the caller signals and waits.
struct Running {
  pid_t pid = -1;
  fs::path err;
  Running(const std::vector<std::string>& args, const fs::path& dir,
          const std::vector<std::pair<std::string, std::string>>& env = {}) {
    err = dir / "stderr";
    std::vector<std::string> full = {OITBENCH_EXE};
    full.insert(full.end(), args.begin(), args.end());
    std::fflush(stdout);  // the child's freopen would write this process's buffered output again
    pid = fork();
    if (pid == 0) {
      for (const auto& [k, v] : env) setenv(k.c_str(), v.c_str(), 1);
      FILE* e = std::freopen(err.c_str(), "w", stderr);
      FILE* o = std::freopen("/dev/null", "w", stdout);
      (void)e;
      (void)o;
      std::vector<char*> argv;
      for (auto& a : full) argv.push_back(a.data());
      argv.push_back(nullptr);
      execv(argv[0], argv.data());
      _exit(127);
    }
  }
  // The exit code, or -1 after `timeout_s` (then the process is killed).
  int wait(double timeout_s) {
    auto t0 = Clock::now();
    int status = 0;
    while (std::chrono::duration<double>(Clock::now() - t0).count() < timeout_s) {
      if (waitpid(pid, &status, WNOHANG) == pid)
        return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    kill(pid, SIGKILL);
    waitpid(pid, &status, 0);
    return -1;
  }
  bool wait_for(const std::function<bool()>& ready, double timeout_s) const {
    auto t0 = Clock::now();
    while (std::chrono::duration<double>(Clock::now() - t0).count() < timeout_s) {
      if (ready()) return true;
      if (waitpid(pid, nullptr, WNOHANG) == pid) return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return false;
  }
  std::string stderr_text() const { return slurp(err); }
};

size_t data_rows(const fs::path& csv) {
  std::error_code ec;
  if (!fs::exists(csv, ec)) return 0;
  auto rows = read_csv_rows(csv);
  return rows.size();
}

// A case whose one repetition runs for minutes on llvmpipe: the hang fault's shader loop (65535
// iterations per fragment, PLATFORM.md) at 1200x900, nine times the watchdog test's 400x300 (~35 s
// there on a quiet machine): about five minutes, one draw.
std::vector<std::string> long_repetition_run(const fs::path& out) {
  return {"run",
          "occupancy",
          "--set",
          "variant=dynamic",
          "--set",
          "size=1",
          "--set",
          "fault=none,hang",
          "--max-sample-ms",  // the hung repetition keeps all its draws
          "0",
          "--resolution",
          "1200x900",
          "--reps",
          "1",
          "--warmup",
          "0",
          "--no-interleave",
          "--isolate",
          "never",
          "--timeout",
          "3600",
          "--out",
          out.string()};
}

TEST(Faults, CtrlCEndsALongRepetitionWithinSecondsAndKeepsTheFinishedRow) {
  auto dir = temp_dir("ctrl-c");
  auto out = dir / "run.csv";
  Running run(long_repetition_run(out), dir);
  ASSERT_TRUE(run.wait_for([&] { return data_rows(out) >= 1; }, 300)) << run.stderr_text();
  // Well inside the hung case's one repetition: the heartbeat shows it is alive.
  ASSERT_TRUE(run.wait_for([&] { return contains(run.stderr_text(), "still running"); }, 60)) << run.stderr_text();
  auto t0 = Clock::now();
  kill(run.pid, SIGINT);
  int code = run.wait(60);
  double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  std::printf("[ measured ] Ctrl-C to exit during a long repetition: %.2f s\n", seconds);
  EXPECT_EQ(code, 130) << run.stderr_text();
  EXPECT_LT(seconds, 5.0 + 5.0) << "the goal is 5 s; the slack is for a busy 2-core machine";
  EXPECT_TRUE(contains(run.stderr_text(), "interrupted")) << run.stderr_text();
  auto rows = read_csv_rows(out);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0]["fault"], "none");
  EXPECT_EQ(rows[0]["status"], "ok");
}

TEST(Faults, ASecondCtrlCEndsTheRunAtOnce) {
  auto dir = temp_dir("ctrl-c-twice");
  auto out = dir / "run.csv";
  Running run(long_repetition_run(out), dir);
  ASSERT_TRUE(run.wait_for([&] { return data_rows(out) >= 1; }, 300)) << run.stderr_text();
  std::this_thread::sleep_for(std::chrono::seconds(1));
  kill(run.pid, SIGINT);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  auto t0 = Clock::now();
  kill(run.pid, SIGINT);
  int code = run.wait(60);
  double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  std::printf("[ measured ] second Ctrl-C to exit: %.2f s\n", seconds);
  EXPECT_EQ(code, 130) << run.stderr_text();
  // The goal is 2 s; the slack is for a busy 2-core machine (2.03 s was measured under a parallel build).
  EXPECT_LT(seconds, 2.0 + 3.0);
  EXPECT_TRUE(contains(run.stderr_text(), "interrupted again")) << run.stderr_text();
  EXPECT_EQ(read_csv_rows(out).size(), 1u);
}

// ---- isolated cases

std::vector<pid_t> processes_mentioning(const std::string& needle) {
  std::vector<pid_t> out;
  for (const auto& e : fs::directory_iterator("/proc")) {
    const std::string name = e.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::string cmdline = slurp(e.path() / "cmdline");
    if (cmdline.find(needle) != std::string::npos) out.push_back(std::stoi(name));
  }
  return out;
}

TEST(Faults, AKilledParentTakesItsIsolatedCaseWithItAndTheNextRunRemovesItsFolder) {
  auto dir = temp_dir("isolated");
  auto tmp = dir / "tmp";
  fs::create_directories(tmp);
  auto out = dir / "run.csv";
  Running run({"run",   "occupancy",       "--quick", "--resolution", "400x300",    "--set",        "variant=dynamic",
               "--set", "size=1",          "--set",   "fault=hang",   "--isolate",  "always",       "--timeout",
               "600",   "--max-sample-ms", "0",       "--out",        out.string(), "--no-progress"},
              dir, {{"TMPDIR", tmp.string()}});
  fs::path case_dir;
  ASSERT_TRUE(run.wait_for(
      [&] {
        for (const auto& e : fs::directory_iterator(tmp))
          if (e.path().filename().string().starts_with("oitbench-case-")) case_dir = e.path();
        return !case_dir.empty() && !processes_mentioning(case_dir.string()).empty();
      },
      120))
      << run.stderr_text();
  std::this_thread::sleep_for(std::chrono::seconds(1));
  kill(run.pid, SIGKILL);
  EXPECT_EQ(run.wait(30), 128 + SIGKILL);
  // The child (its command line names the case folder) dies with its parent.
  auto t0 = Clock::now();
  while (!processes_mentioning(case_dir.string()).empty() &&
         std::chrono::duration<double>(Clock::now() - t0).count() < 5)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  std::printf("[ measured ] isolated child gone %.2f s after its parent's SIGKILL\n", seconds);
  EXPECT_TRUE(processes_mentioning(case_dir.string()).empty()) << "the isolated case outlived its parent";
  EXPECT_TRUE(fs::exists(case_dir)) << "a SIGKILLed parent cannot remove it: the next run does";
  // The next run under the same TMPDIR that isolates a case removes the folder of the dead one.
  Running again({"run", "occupancy", "--quick", "--set", "variant=dynamic", "--set", "size=1", "--isolate", "always",
                 "--out", (dir / "again.csv").string(), "--no-progress"},
                dir, {{"TMPDIR", tmp.string()}});
  EXPECT_EQ(again.wait(300), 0) << again.stderr_text();
  EXPECT_FALSE(fs::exists(case_dir)) << case_dir;
  size_t left = 0;
  for (const auto& e : fs::directory_iterator(tmp)) left += e.path().filename().string().starts_with("oitbench-case-");
  EXPECT_EQ(left, 0u);
}

// ---- render targets past the driver's limits

class RenderTargetLimits : public GlTest {};

TEST_F(RenderTargetLimits, PastTheLimitsIsUnavailableNamingTheLimit) {
  const long long max = gl().limit("GL_MAX_TEXTURE_SIZE");
  ASSERT_GT(max, 0);
  const int past = static_cast<int>(max) + 1;
  auto why = render_target_size_problem(past, 16);
  EXPECT_TRUE(contains(why, "is past GL_MAX")) << why;
  EXPECT_TRUE(render_target_size_problem(64, 64).empty());
  try {
    RenderTarget t(past, 16);
    FAIL() << "a render target past GL_MAX_TEXTURE_SIZE was made";
  } catch (const RenderTargetUnavailable& e) {
    EXPECT_TRUE(contains(e.what(), std::to_string(past))) << e.what();
  }
}

TEST(Faults, AResolutionTheDriverCannotAllocateIsUnsupportedNotAnError) {
  // 12000x12000 RGBA32F is 2.3 GB: llvmpipe refuses the texture (the "about 11600^2"); a GPU with
  // the memory runs it. Either way never an `error` row with a framebuffer status in decimal.
  auto out = temp_dir("huge") / "h.csv";
  auto r = run_oitbench({"run", "occupancy", "--set", "variant=dynamic", "--set", "size=1", "--resolution",
                         "12000x12000", "--reps", "1", "--warmup", "0", "--out", out.string(), "--no-progress"},
                        300);
  auto rows = read_csv_rows(out);
  ASSERT_EQ(rows.size(), 1u) << r.err;
  EXPECT_NE(rows[0]["status"], "error") << rows[0]["reason"];
  if (rows[0]["status"] == "unsupported") {
    EXPECT_EQ(r.exit_code, 3) << r.err;
    EXPECT_TRUE(contains(rows[0]["reason"], "render target 12000x12000")) << rows[0]["reason"];
  }
}

}  // namespace
}  // namespace oitbench::test
