#include "core/runner.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <condition_variable>
#include <mutex>
#include <set>
#include <sstream>
#include <thread>

#include "core/data_dirs.hpp"
#include "core/csv.hpp"
#include "core/stats.hpp"

namespace oitbench {

namespace {

// The one piece of process-wide state: async-signal-safe flags set by SIGINT/SIGTERM.
volatile std::sig_atomic_t g_stop_signal = 0;
extern "C" void on_stop_signal(int sig) { g_stop_signal = sig; }

class SignalGuard {
 public:
  SignalGuard() {
    struct sigaction sa {};
    sa.sa_handler = on_stop_signal;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, &old_int_);
    sigaction(SIGTERM, &sa, &old_term_);
  }
  ~SignalGuard() {
    sigaction(SIGINT, &old_int_, nullptr);
    sigaction(SIGTERM, &old_term_, nullptr);
  }
  bool stopped() const { return g_stop_signal != 0; }

 private:
  struct sigaction old_int_ {}, old_term_ {};
};

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

std::string fmt(double v, int prec = 4) {
  if (!std::isfinite(v)) return "";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", prec + 3, v);
  return buf;
}

std::string utc_now() {
  auto t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("model name", 0) == 0) {
      auto c = line.find(':');
      return c == std::string::npos ? "" : line.substr(c + 2);
    }
  return "";
}

// Environment that changes a driver's speed or behaviour: recorded in every row.
std::string recorded_env() {
  static const char* names[] = {"LP_NATIVE_VECTOR_WIDTH", "GALLIUM_DRIVER", "LIBGL_ALWAYS_SOFTWARE",
                                "MESA_SHADER_CACHE_DISABLE", "MESA_SHADER_CACHE_DIR", "MESA_GL_VERSION_OVERRIDE",
                                "MESA_LOADER_DRIVER_OVERRIDE", "EGL_PLATFORM", "__GL_THREADED_OPTIMIZATIONS",
                                "__GL_SHADER_DISK_CACHE", "OITBENCH_SHADERS"};
  std::string s;
  for (const char* n : names)
    if (const char* v = std::getenv(n)) s += (s.empty() ? "" : ";") + std::string(n) + "=" + v;
  return s;
}

std::string lp_num_threads() {
  if (const char* v = std::getenv("LP_NUM_THREADS")) return v;
  return "unset(" + std::to_string(std::thread::hardware_concurrency()) + " cores)";
}

const std::vector<std::string>& base_columns() {
  static const std::vector<std::string> cols = {
      "schema", "experiment", "variant", "pass", "status", "valid", "reason", "backend", "device", "gl_vendor",
      "gl_renderer", "gl_version", "width", "height", "reps", "warmup", "median_ms", "mad_ms", "min_ms", "max_ms",
      "mean_ms", "stddev_ms", "samples", "outliers", "cpu_median_ms", "cpu_mad_ms", "gpu_median_ms", "gpu_mad_ms",
      "timer", "compile_ms", "program_cache", "warmup_ms", "preset", "git_sha", "timestamp_utc", "hostname", "cpu_model",
      "lp_num_threads", "env", "parameters"};
  return cols;
}

void append_unique(std::vector<std::string>& v, const std::string& s) {
  if (std::find(v.begin(), v.end(), s) == v.end()) v.push_back(s);
}

// --- one case in flight ---
struct LiveCase {
  ParamSet params;
  std::string variant;
  std::unique_ptr<CaseInstance> instance;
  std::string status = "ok";
  std::string reason;
  double compile_ms = NAN, warmup_ms = NAN;
  std::string program_cache;  // hit | miss | partial | off: whether compile_ms paid the compile
  std::vector<std::string> pass_names;
  std::map<std::string, std::vector<double>> cpu, gpu;  // by pass, "total" included
  Validation validation;
  bool done = false;  // its rows are written
};

std::string gl_error_text() {
  std::string s;
  for (GLenum e; (e = glGetError()) != GL_NO_ERROR;) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "0x%04x", e);
    s += (s.empty() ? "" : ",") + std::string(buf);
  }
  return s;
}

class Runner {
 public:
  Runner(Registry& registry, const RunOptions& options) : registry_(registry), opt_(options) {}

  int run(const std::vector<RunRequest>& requests) {
    ctx_ = create_context(opt_.context);
    gl_ = GlInfo::query();
    shaders_ = std::make_unique<ShaderLibrary>(opt_.shader_root);
    if (opt_.program_cache && gl_.has_extension("GL_ARB_get_program_binary"))
      shaders_->enable_program_cache(default_program_cache_dir(), gl_.vendor + "|" + gl_.renderer + "|" + gl_.version);
    use_gpu_timer_ = opt_.timer == "gpu" || (opt_.timer == "auto" && !gl_.is_software_renderer() && gl_.has_timer_query());
    writer_ = std::make_unique<CsvWriter>(opt_.out, csv_columns(registry_));
    if (!opt_.raw.empty()) raw_writer_ = std::make_unique<CsvWriter>(opt_.raw, raw_columns(registry_));
    meta_ = {{"schema", std::to_string(kCsvSchema)}, {"backend", ctx_->backend()}, {"device", ctx_->device()},
             {"gl_vendor", gl_.vendor}, {"gl_renderer", gl_.renderer}, {"gl_version", gl_.version},
             {"git_sha", git_sha()}, {"hostname", hostname()}, {"cpu_model", cpu_model()},
             {"lp_num_threads", lp_num_threads()}, {"env", recorded_env()}, {"preset", opt_.preset_name}};

    // Expand every request first so progress can say "case i of n".
    struct Planned {
      Experiment* exp;
      Resolution res;
      int reps, warmup;
      std::vector<ParamSet> cases;
    };
    std::vector<Planned> plan;
    for (const auto& r : requests) {
      Experiment* e = registry_.find(r.experiment);
      const bool quick = opt_.quick || r.quick;
      Resolution res = opt_.resolution ? *opt_.resolution
                       : r.resolution  ? *r.resolution
                       : quick         ? e->quick_resolution()
                                       : e->default_resolution();
      int reps = opt_.reps_given ? opt_.reps : r.reps.value_or(quick ? std::min(opt_.reps, 3) : opt_.reps);
      int warmup = opt_.warmup_given ? opt_.warmup : r.warmup.value_or(opt_.warmup);
      plan.push_back({e, res, reps, warmup, expand_grid(registry_.params_of(*e), r.overrides, quick)});
      total_cases_ += plan.back().cases.size();
    }
    start_ = Clock::now();
    watchdog_ = std::thread([this] { watch(); });
    for (auto& p : plan) {
      if (signals_.stopped()) break;
      bool isolate = opt_.isolate == "always" || (opt_.isolate == "auto" && p.exp->hang_prone());
      if (isolate) {
        for (auto& c : p.cases) {
          if (signals_.stopped()) break;
          run_isolated(*p.exp, p.res, p.reps, p.warmup, c);
        }
      } else {
        size_t chunk = opt_.interleave ? static_cast<size_t>(std::max(1, p.exp->max_interleave())) : 1;
        for (size_t i = 0; i < p.cases.size() && !signals_.stopped(); i += chunk) {
          std::vector<ParamSet> group(p.cases.begin() + static_cast<std::ptrdiff_t>(i),
                                      p.cases.begin() + static_cast<std::ptrdiff_t>(std::min(p.cases.size(), i + chunk)));
          run_group(*p.exp, p.res, p.reps, p.warmup, group);
        }
      }
    }
    {
      std::lock_guard lock(mutex_);
      finished_ = true;
    }
    watchdog_cv_.notify_all();
    watchdog_.join();
    if (opt_.progress) std::fputc('\n', stderr);
    if (!opt_.isolated_child)
      std::fprintf(stderr, "oitbench: %zu case(s): %d ok, %d invalid, %d unsupported, %d error, %d timeout -> %s\n",
                 cases_done_, counts_["ok"], counts_["invalid"], counts_["unsupported"], counts_["error"],
                 counts_["timeout"], opt_.out == "-" ? "stdout" : opt_.out.c_str());
    if (signals_.stopped()) {
      std::fprintf(stderr, "oitbench: interrupted; the %zu finished row(s) are in %s\n", writer_->rows_written(),
                   opt_.out.c_str());
      return 130;
    }
    if (counts_["error"] + counts_["timeout"] > 0) return 1;
    if (cases_done_ > 0 && counts_["unsupported"] == static_cast<int>(cases_done_)) return 3;
    return 0;
  }

 private:
  static std::string hostname() {
    char buf[256] = {};
    gethostname(buf, sizeof buf - 1);
    return buf;
  }

  std::string variant_of(const ParamSet& p) const { return p.has("variant") ? p.get("variant") : ""; }

  void run_group(Experiment& exp, Resolution res, int reps, int warmup, const std::vector<ParamSet>& group) {
    std::vector<LiveCase> live(group.size());
    for (size_t i = 0; i < group.size(); ++i) {
      auto& c = live[i];
      c.params = group[i];
      c.variant = variant_of(c.params);
      set_current(exp.name() + " " + c.params.describe());
      if (auto why = exp.unsupported_reason(gl_, c.params); !why.empty()) {
        fail(c, "unsupported", why);
        continue;
      }
      try {
        CaseContext cctx(*shaders_, gl_, res, c.params.get("fault"), static_cast<unsigned>(c.params.get_int("seed")));
        glFinish();
        auto t0 = Clock::now();
        auto before = shaders_->cache_counts();
        c.instance = exp.prepare(c.params, cctx);
        glFinish();
        c.compile_ms = ms_since(t0);
        auto after = shaders_->cache_counts();
        unsigned hits = after.hits - before.hits, misses = after.misses - before.misses;
        c.program_cache = !opt_.program_cache ? "off"
                          : hits + misses == 0 ? ""
                          : misses == 0        ? "hit"
                          : hits == 0          ? "miss"
                                               : "partial";
        if (auto err = gl_error_text(); !err.empty()) fail(c, "error", "GL error after prepare: " + err);
      } catch (const Unsupported& e) {
        fail(c, "unsupported", e.what());
      } catch (const std::exception& e) {
        fail(c, "error", e.what());
        std::fprintf(stderr, "\noitbench: %s %s: %s\n", exp.name().c_str(), c.params.describe().c_str(), e.what());
      }
    }
    auto active = [&](const LiveCase& c) { return c.instance && c.status == "ok"; };
    PassTimer timer(gl_.has_timer_query());  // queries recorded always; primary only where trusted
    // Warm-up, then timed repetitions, interleaved across the group: A B C A B C ...
    for (int r = -warmup; r < reps && !signals_.stopped(); ++r) {
      for (auto& c : live) {
        if (!active(c) || signals_.stopped()) continue;
        set_current(exp.name() + " " + c.params.describe());
        try {
          timer.begin_repetition();
          glFinish();
          auto t0 = Clock::now();
          c.instance->run(timer);
          glFinish();
          double total = ms_since(t0);
          auto samples = timer.end_repetition();
          if (auto err = gl_error_text(); !err.empty()) {
            fail(c, "error", "GL error during run: " + err);
            continue;
          }
          if (r == -warmup) c.warmup_ms = total;
          if (r < 0) continue;
          double gpu_total = samples.empty() ? -1 : 0;
          for (const auto& s : samples) {
            append_unique(c.pass_names, s.pass);
            c.cpu[s.pass].push_back(s.cpu_ms);
            c.gpu[s.pass].push_back(s.gpu_ms);
            gpu_total = (gpu_total < 0 || s.gpu_ms < 0) ? -1 : gpu_total + s.gpu_ms;
          }
          c.cpu["total"].push_back(total);
          c.gpu["total"].push_back(gpu_total);
          write_raw(exp, c, r, samples, total, gpu_total);
        } catch (const std::exception& e) {
          fail(c, "error", std::string("run: ") + e.what());
        }
      }
      progress(exp, live, r + warmup + 1, reps + warmup);
    }
    if (signals_.stopped()) return;  // unfinished cases write nothing; finished rows are on disk
    for (auto& c : live) {
      if (active(c)) {
        try {
          c.validation = c.instance->validate();
          if (!c.validation.valid) fail(c, "invalid", c.validation.reason);
        } catch (const std::exception& e) {
          fail(c, "error", std::string("validate: ") + e.what());
        }
      }
      write_rows(exp, res, reps, warmup, c);
      c.instance.reset();
    }
  }

  void fail(LiveCase& c, const std::string& status, const std::string& reason) {
    if (c.status != "ok") return;  // the first failure is the one worth reporting
    c.status = status;
    c.reason = reason;
  }

  std::map<std::string, std::string> common_row(Experiment& exp, Resolution res, int reps, int warmup,
                                                const LiveCase& c) {
    auto row = meta_;
    row["experiment"] = exp.name();
    row["variant"] = c.variant;
    row["width"] = std::to_string(res.width);
    row["height"] = std::to_string(res.height);
    row["reps"] = std::to_string(reps);
    row["warmup"] = std::to_string(warmup);
    row["timestamp_utc"] = utc_now();
    std::string names;
    for (const auto& [k, v] : c.params.values())
      if (k != "variant") {
        row[k] = v;
        names += (names.empty() ? "" : ";") + k;
      }
    row["parameters"] = names;  // which of the columns after the base ones are this case's parameters
    return row;
  }

  void write_rows(Experiment& exp, Resolution res, int reps, int warmup, LiveCase& c) {
    auto base = common_row(exp, res, reps, warmup, c);
    base["status"] = c.status;
    base["valid"] = c.status == "ok" ? "1" : "0";
    base["compile_ms"] = fmt(c.compile_ms);
    base["warmup_ms"] = fmt(c.warmup_ms);
    base["program_cache"] = c.program_cache;
    if (c.instance)
      for (const auto& [k, v] : c.instance->metrics()) base[k] = v;
    for (const auto& [k, v] : c.validation.metrics) base[k] = v;
    std::vector<std::string> passes;
    if (c.pass_names.size() > 1) passes = c.pass_names;
    passes.push_back("total");
    std::lock_guard lock(mutex_);
    for (const auto& pass : passes) {
      auto row = base;
      row["pass"] = pass;
      std::string reason = c.status == "ok" ? c.validation.reason : c.reason;
      if (c.status == "ok" && c.cpu.count(pass)) {
        auto cs = summarize(c.cpu[pass]);
        std::vector<double> g;
        for (double x : c.gpu[pass])
          if (x >= 0) g.push_back(x);
        bool have_gpu = !g.empty() && g.size() == c.gpu[pass].size();
        auto gs = have_gpu ? summarize(g) : Summary{};
        bool gpu_primary = use_gpu_timer_ && have_gpu;
        const auto& s = gpu_primary ? gs : cs;
        row["timer"] = gpu_primary ? "gpu" : "cpu";
        row["median_ms"] = fmt(s.median);
        row["mad_ms"] = fmt(s.mad);
        row["min_ms"] = fmt(s.min);
        row["max_ms"] = fmt(s.max);
        row["mean_ms"] = fmt(s.mean);
        row["stddev_ms"] = fmt(s.stddev);
        row["samples"] = std::to_string(s.n);
        row["outliers"] = std::to_string(s.outliers);
        row["cpu_median_ms"] = fmt(cs.median);
        row["cpu_mad_ms"] = fmt(cs.mad);
        if (have_gpu) {
          row["gpu_median_ms"] = fmt(gs.median);
          row["gpu_mad_ms"] = fmt(gs.mad);
        }
        // Where queries are the primary clock, a CPU clock far off them means one of them is wrong.
        if (gpu_primary && gs.median > 0 && (cs.median / gs.median > kTimerDisagreement ||
                                             gs.median / cs.median > kTimerDisagreement)) {
          reason += (reason.empty() ? "" : "; ") + std::string("timer-disagreement: cpu ") + fmt(cs.median, 3) +
                    " ms vs gpu " + fmt(gs.median, 3) + " ms";
        }
      }
      row["reason"] = reason;
      writer_->write(row);
    }
    ++counts_[c.status];
    ++cases_done_;
    c.done = true;
  }

  void write_raw(Experiment& exp, const LiveCase& c, int rep, const std::vector<PassSample>& samples, double total,
                 double gpu_total) {
    if (!raw_writer_) return;
    std::map<std::string, std::string> row = {
        {"schema", std::to_string(kCsvSchema)}, {"experiment", exp.name()}, {"variant", c.variant},
        {"backend", ctx_->backend()}, {"gl_renderer", gl_.renderer}, {"git_sha", git_sha()},
        {"rep", std::to_string(rep)}, {"timestamp_utc", utc_now()}, {"preset", opt_.preset_name}};
    for (const auto& [k, v] : c.params.values())
      if (k != "variant") row[k] = v;
    std::lock_guard lock(mutex_);
    auto put = [&](const std::string& pass, double cpu, double gpu) {
      row["pass"] = pass;
      row["cpu_ms"] = fmt(cpu);
      row["gpu_ms"] = gpu >= 0 ? fmt(gpu) : "";
      raw_writer_->write(row);
    };
    if (samples.size() > 1)
      for (const auto& s : samples) put(s.pass, s.cpu_ms, s.gpu_ms);
    put("total", total, gpu_total);
  }

  // A case in a child process (`oitbench run EXP --set k=v ... --isolate never`), killed by the
  // watchdog when it exceeds --timeout: spinlock variants can hang a real GPU.
  void run_isolated(Experiment& exp, Resolution res, int reps, int warmup, const ParamSet& params) {
    set_current(exp.name() + " " + params.describe());
    const char* tmpdir = std::getenv("TMPDIR");
    std::string dir_tmpl = std::string(tmpdir ? tmpdir : "/tmp") + "/oitbench-case-XXXXXX";
    std::vector<char> dbuf(dir_tmpl.begin(), dir_tmpl.end());
    dbuf.push_back('\0');
    if (!mkdtemp(dbuf.data())) throw std::runtime_error("cannot create a temporary directory for an isolated case");
    std::string dir = dbuf.data();
    std::string out = dir + "/case.csv", raw = dir + "/raw.csv";
    std::vector<std::string> args = {"/proc/self/exe", "run", exp.name(), "--out", out, "--isolate", "never",
                                     "--no-progress", "--isolated-child", "--backend", opt_.context.backend,
                                     "--device", std::to_string(opt_.context.device),
                                     "--resolution", std::to_string(res.width) + "x" + std::to_string(res.height),
                                     "--reps", std::to_string(reps), "--warmup", std::to_string(warmup),
                                     "--timer", opt_.timer, "--shaders", opt_.shader_root};
    if (!opt_.preset_name.empty()) args.insert(args.end(), {"--preset-name", opt_.preset_name});
    if (raw_writer_) args.insert(args.end(), {"--raw", raw});
    if (!opt_.interleave) args.push_back("--no-interleave");
    if (!opt_.program_cache) args.push_back("--no-program-cache");
    for (const auto& [k, v] : params.values()) args.insert(args.end(), {"--set", k + "=" + v});
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_t pid = fork();
    if (pid == 0) {
      setpgid(0, 0);
      execv(argv[0], argv.data());
      _exit(127);
    }
    auto t0 = Clock::now();
    int status = 0;
    bool timed_out = false;
    for (;;) {
      pid_t w = waitpid(pid, &status, WNOHANG);
      if (w == pid) break;
      if (signals_.stopped() || ms_since(t0) > opt_.timeout_s * 1000) {
        timed_out = !signals_.stopped();
        kill(-pid, SIGKILL);
        kill(pid, SIGKILL);
        waitpid(pid, &status, 0);
        break;
      }
      heartbeat();  // the child has its own deadline; the in-process watchdog must not race it
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    heartbeat();
    bool copied = false;
    if (!timed_out && !signals_.stopped()) copied = copy_rows(out, *writer_) > 0;
    if (copied && raw_writer_) copy_rows(raw, *raw_writer_);
    if (!copied && !signals_.stopped()) {
      LiveCase c;
      c.params = params;
      c.variant = variant_of(params);
      if (timed_out) {
        fail(c, "timeout", "killed by the watchdog after " + fmt(opt_.timeout_s, 3) + " s (--timeout)");
      } else if (WIFSIGNALED(status)) {
        fail(c, "error", "the case's process died with signal " + std::to_string(WTERMSIG(status)));
      } else {
        fail(c, "error", "the case's process exited with code " + std::to_string(WEXITSTATUS(status)) + " and no rows");
      }
      write_rows(exp, res, reps, warmup, c);
    }
    std::filesystem::remove_all(dir);
    progress(exp, {}, 1, 1);
  }

  size_t copy_rows(const std::string& path, CsvWriter& into) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return 0;
    std::stringstream ss;
    ss << in.rdbuf();
    auto rows = csv_parse(ss.str());
    if (rows.size() < 2) return 0;
    const auto& header = rows[0];
    std::lock_guard lock(mutex_);
    for (size_t i = 1; i < rows.size(); ++i) {
      std::map<std::string, std::string> row;
      for (size_t j = 0; j < header.size() && j < rows[i].size(); ++j) row[header[j]] = rows[i][j];
      into.write(row);
      if (&into == writer_.get() && row["pass"] == "total") {
        ++counts_[row["status"]];
        ++cases_done_;
      }
    }
    return rows.size() - 1;
  }

  void progress(Experiment& exp, const std::vector<LiveCase>& group, int step, int steps) {
    heartbeat();
    if (!opt_.progress) return;
    double elapsed = ms_since(start_) / 1000.0;
    // The group's cases are not counted in cases_done_ until it ends, its last repetition included.
    const bool in_group = !group.empty();
    double done = static_cast<double>(cases_done_) +
                  (in_group ? static_cast<double>(group.size()) * std::min(step, steps) / std::max(steps, 1) : 0.0);
    double frac = done / static_cast<double>(std::max<size_t>(total_cases_, 1));
    char eta[32] = "?";
    if (frac > 0.005) std::snprintf(eta, sizeof eta, "%.0f s", elapsed / frac - elapsed);
    char cases[64];
    if (in_group && group.size() > 1)
      std::snprintf(cases, sizeof cases, "cases %zu-%zu of %zu", cases_done_ + 1, cases_done_ + group.size(), total_cases_);
    else
      std::snprintf(cases, sizeof cases, "case %zu of %zu", std::min(cases_done_ + (in_group ? 1 : 0), total_cases_),
                    total_cases_);  // between groups: the last finished one
    std::fprintf(stderr, "\r[%s] %s  rep %d/%d  elapsed %.1f s  remaining ~%s   ", cases, exp.name().c_str(), step,
                 steps, elapsed, eta);
    if (!isatty(STDERR_FILENO)) std::fputc('\n', stderr);
    std::fflush(stderr);
  }

  void set_current(const std::string& what) {
    std::lock_guard lock(mutex_);
    current_ = what;
    last_beat_ = Clock::now();
  }
  void heartbeat() {
    std::lock_guard lock(mutex_);
    last_beat_ = Clock::now();
  }

  // In-process watchdog: a GPU call that does not return within --timeout cannot be cancelled,
  // so the run ends with a clear message (the finished rows are already on disk).
  void watch() {
    std::unique_lock lock(mutex_);
    while (!finished_) {
      watchdog_cv_.wait_for(lock, std::chrono::milliseconds(200));
      if (finished_) break;
      if (std::chrono::duration<double>(Clock::now() - last_beat_).count() > opt_.timeout_s) {
        std::fprintf(stderr,
                     "\noitbench: watchdog: '%s' made no progress for %.0f s (--timeout); stopping. "
                     "Finished rows are in %s; hang-prone experiments run isolated (--isolate always).\n",
                     current_.c_str(), opt_.timeout_s, opt_.out.c_str());
        std::_Exit(1);
      }
    }
  }

  static constexpr double kTimerDisagreement = 2.0;

  Registry& registry_;
  const RunOptions& opt_;
  SignalGuard signals_;
  std::unique_ptr<Context> ctx_;
  GlInfo gl_;
  std::unique_ptr<ShaderLibrary> shaders_;
  bool use_gpu_timer_ = false;
  std::unique_ptr<CsvWriter> writer_, raw_writer_;
  std::map<std::string, std::string> meta_;
  std::map<std::string, int> counts_;
  size_t total_cases_ = 0, cases_done_ = 0;
  Clock::time_point start_;
  std::mutex mutex_;
  std::condition_variable watchdog_cv_;
  std::thread watchdog_;
  bool finished_ = false;
  std::string current_;
  Clock::time_point last_beat_ = Clock::now();
};

}  // namespace

std::vector<std::string> csv_columns(const Registry& registry) {
  auto cols = base_columns();
  for (const auto& e : registry.all())
    for (const auto& m : e->metric_columns()) append_unique(cols, m);
  for (const auto& e : registry.all())
    for (const auto& p : registry.params_of(*e))
      if (p.name != "variant") append_unique(cols, p.name);
  return cols;
}

std::vector<std::string> raw_columns(const Registry& registry) {
  std::vector<std::string> cols = {"schema", "experiment", "variant", "pass", "rep", "cpu_ms", "gpu_ms", "backend",
                                   "gl_renderer", "git_sha", "timestamp_utc", "preset"};
  for (const auto& e : registry.all())
    for (const auto& p : registry.params_of(*e))
      if (p.name != "variant") append_unique(cols, p.name);
  return cols;
}

void check_requests(const Registry& registry, const std::vector<RunRequest>& requests) {
  if (requests.empty()) throw UsageError("nothing to run; experiments: " + registry.names());
  for (const auto& r : requests) {
    const Experiment* e = registry.find(r.experiment);
    if (!e) throw UsageError("unknown experiment '" + r.experiment + "'; valid experiments: " + registry.names() + ", all");
    auto specs = registry.params_of(*e);
    for (const auto& [name, values] : r.overrides) {
      auto it = std::find_if(specs.begin(), specs.end(), [&](const ParamSpec& s) { return s.name == name; });
      if (it == specs.end()) {
        std::string valid;
        for (const auto& s : specs) valid += (valid.empty() ? "" : ", ") + s.name;
        throw UsageError("experiment '" + e->name() + "' has no parameter '" + name + "'; valid parameters: " + valid);
      }
      for (const auto& v : values) it->check(v, e->name());
    }
  }
}

int run_experiments(Registry& registry, const std::vector<RunRequest>& requests, const RunOptions& options) {
  check_requests(registry, requests);
  Runner runner(registry, options);
  return runner.run(requests);
}

std::string default_shader_root() { return data_dir("shaders"); }

}  // namespace oitbench
