#include "core/runner.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <mutex>
#include <sstream>

#include "backends/drivers.hpp"
#include "core/csv.hpp"
#include "core/data_dirs.hpp"
#include "core/gpu_state.hpp"
#include "core/groups.hpp"
#include "core/interrupt.hpp"
#include "core/isolation.hpp"
#include "core/memory_probe.hpp"
#include "core/outcomes.hpp"
#include "core/phases.hpp"
#include "core/plan.hpp"
#include "core/progress.hpp"
#include "core/rows.hpp"
#include "gl/render_target.hpp"

namespace oitbench {

namespace {

// The DRM node and PCI bus of the EGL device a context runs on ({"", ""} where unknown): --backend
// egl-device's --device, or device 0 where the egl backend fell back to the device platform.
std::pair<std::string, std::string> device_node(const ContextOptions& o, const std::string& device_words) {
  int index = -1;
  if (o.backend == "egl-device")
    index = o.device;
  else if (device_words.rfind("EGL device 0 ", 0) == 0)
    index = 0;
  if (index < 0) return {"", ""};
  for (const auto& d : list_egl_devices())
    if (d.index == index) return {d.drm_file.empty() ? d.render_node : d.drm_file, d.pci_bus};
  return {"", ""};
}

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

std::string gl_error_text() {
  std::string s;
  for (GLenum e; (e = glGetError()) != GL_NO_ERROR;) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "0x%04x", e);
    s += (s.empty() ? "" : ",") + std::string(buf);
  }
  return s;
}

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// While alive, the run's clock charges `times`' phase `p`; at its end the group's own work (`after`) again.
class Charging {
 public:
  Charging(PhaseClock& clock, PhaseTimes& times, Phase p, PhaseTimes& after) : clock_(clock), after_(after) {
    clock_.attach(&times, p);
  }
  Charging(const Charging&) = delete;
  Charging& operator=(const Charging&) = delete;
  ~Charging() { clock_.attach(&after_, Phase::Other); }

 private:
  PhaseClock& clock_;
  PhaseTimes& after_;
};

// A case in flight: its record and, while it runs, its instance.
struct LiveCase {
  CaseRecord record;
  std::unique_ptr<CaseInstance> instance;
  bool active() const { return instance && record.status == Status::Ok; }
};

// One sample: `runs` runs of the case's repetition inside one PassTimer repetition, each pass's times
// summed over the runs, divided by them and scaled from `units` to the nominal units of work.
std::vector<PassSample> per_repetition(const std::vector<PassSample>& all, int runs, double scale) {
  std::vector<PassSample> out;
  for (const auto& s : all) {
    auto it = std::find_if(out.begin(), out.end(), [&](const PassSample& o) { return o.pass == s.pass; });
    if (it == out.end()) {
      out.push_back(s);
      continue;
    }
    it->cpu_ms += s.cpu_ms;
    it->gpu_ms = (it->gpu_ms < 0 || s.gpu_ms < 0) ? -1 : it->gpu_ms + s.gpu_ms;
  }
  for (auto& o : out) {
    o.cpu_ms *= scale / runs;
    if (o.gpu_ms >= 0) o.gpu_ms *= scale / runs;
  }
  return out;
}

class Runner {
 public:
  // `expected`: --expect's lines (the patterns no case of the grid matches are warned of).
  Runner(Registry& registry, const RunOptions& options, const std::vector<Expectation>& expected)
      : registry_(registry),
        opt_(options),
        expected_(expected),
        run_id_(options.run_id.empty() ? new_run_id() : options.run_id),
        keep_outcomes_(!options.expect.empty() || !options.junit.empty() || !write_expect_path(options).empty()) {}

  int run(const std::vector<RunRequest>& requests) {
    try {
      ctx_ = create_context(opt_.context);
    } catch (const ContextUnsupported& e) {
      return unsupported_driver(requests, e);
    }
    gl_ = GlInfo::query();
    gpu_ = GpuMonitor::for_gl_context(gl_.vendor, gl_.renderer);
    shaders_ = std::make_unique<ShaderLibrary>(opt_.shader_root);
    if (opt_.program_cache && gl_.has_extension("GL_ARB_get_program_binary"))
      shaders_->enable_program_cache(default_program_cache_dir(), gl_.vendor + "|" + gl_.renderer + "|" + gl_.version);
    use_gpu_timer_ =
        opt_.timer == "gpu" || (opt_.timer == "auto" && !gl_.is_software_renderer() && gl_.has_timer_query());
    // A CPU rasterizer has no pipeline to keep full, and its queries are wrong: bracket every pass.
    sync_passes_ = opt_.sync_passes || gl_.is_software_renderer() || !use_gpu_timer_;
    if (opt_.dry_run) return dry_run(requests);
    writer_ = std::make_unique<CsvWriter>(opt_.out, summary_columns(registry_));
    if (!opt_.raw.empty()) raw_writer_ = std::make_unique<CsvWriter>(opt_.raw, raw_columns(registry_), "--raw");
    run_columns_ = machine_columns();
    const LlvmTarget llvm = llvm_target(gl_.renderer);
    const auto [drm_node, pci_bus] = device_node(opt_.context, ctx_->device());
    const GpuIdentity gpu_id = gpu_identity(gpu_, pci_bus);
    run_columns_.insert({{"backend", ctx_->backend()},
                         {"device_drm_node", drm_node},
                         {"device_pci_bus", pci_bus},
                         {"mesa_version", mesa_version(gl_.version)},
                         {"llvm_version", llvm.llvm_version},
                         {"llvm_vector_bits", llvm.vector_bits},
                         {"device", ctx_->device()},
                         {"driver", driver_slug(gl_)},
                         {"gl_vendor", gl_.vendor},
                         {"gl_renderer", gl_.renderer},
                         {"gl_version", gl_.version},
                         {"gpu_driver_version", gpu_.driver_version()},
                         {"gpu_pci_id", gpu_id.pci_id},
                         {"gpu_vbios_version", gpu_id.vbios_version}});

    // Count every request's cases first (walked, not built) so progress can say "case i of n"; with
    // --shard, this shard's units only. The units are made one at a time as the run reaches them.
    const std::vector<Planned> plan = make_plan(registry_, requests, opt_, !gl_.is_software_renderer());
    note_grid(plan);
    const size_t total_cases = UnitStream(plan, opt_, opt_.shard).count_rows();
    progress_ = std::make_unique<Progress>(opt_.progress, total_cases);
    watchdog_ = std::make_unique<Watchdog>(opt_.timeout_s, opt_.out, opt_.progress);
    account_.start_s = seconds_since(opt_.started);
    UnitStream units(plan, opt_, opt_.shard);
    for (RunUnit u; !signals_.stopped() && units.next(u);) {
      if (u.isolated)
        run_isolated(plan[u.planned], u.group.cases[0]);
      else
        run_group(plan[u.planned], u.group);
    }
    watchdog_.reset();
    progress_->finish();
    if (!opt_.isolated_child)
      std::fprintf(stderr, "oitbench: %zu case(s): %d ok, %d invalid, %d unsupported, %d error, %d timeout -> %s\n",
                   cases_done_, counts_[Status::Ok], counts_[Status::Invalid], counts_[Status::Unsupported],
                   counts_[Status::Error], counts_[Status::Timeout], opt_.out == "-" ? "stdout" : opt_.out.c_str());
    if (!opt_.isolated_child) std::fprintf(stderr, "%s\n", account_.summary_line(seconds_since(opt_.started)).c_str());
    if (signals_.stopped()) {
      std::fprintf(stderr, "oitbench: interrupted; the %zu finished row(s) are in %s\n", writer_->rows_written(),
                   opt_.out.c_str());
      return 130;
    }
    if (counts_[Status::Error] + counts_[Status::Timeout] > 0) return 1;
    if (cases_done_ > 0 && counts_[Status::Unsupported] == static_cast<int>(cases_done_)) return 3;
    return 0;
  }

 private:
  // The driver gives no GL 4.5 core context: every case is `unsupported`, with the version it offered.
  int unsupported_driver(const std::vector<RunRequest>& requests, const ContextUnsupported& e) {
    writer_ = std::make_unique<CsvWriter>(opt_.out, summary_columns(registry_));
    run_columns_ = machine_columns();
    run_columns_.insert(
        {{"backend", opt_.context.backend}, {"driver", opt_.context.driver}, {"gl_version", e.offered()}});
    size_t cases = 0;
    // Without a context the entry's own sizes (a software renderer's).
    const std::vector<Planned> plan = make_plan(registry_, requests, opt_, false);
    note_grid(plan);
    UnitStream units(plan, opt_, opt_.shard);
    for (RunUnit u; units.next(u);)
      for (size_t i = 0; i < u.group.cases.size(); ++i) {
        if (u.group.shadow[i]) continue;
        CaseRecord rec = new_record(u.group.cases[i], plan[u.planned]);
        rec.fail(Status::Unsupported, e.what());
        finish_case(row_settings(plan[u.planned]), rec);
        ++cases;
      }
    std::fprintf(stderr, "oitbench: %s: %zu case(s) unsupported -> %s\n", e.what(), cases,
                 opt_.out == "-" ? "stdout" : opt_.out.c_str());
    return 3;
  }

  // The run's columns that do not depend on the context: schema, code, machine, environment, preset.
  Row machine_columns() const {
    const MachineIdentity m = this_machine();
    return {{"schema", std::to_string(kCsvSchema)},
            {"run_id", run_id_},
            {"tags", encode_tags(opt_.tags)},
            {"git_sha", git_sha()},
            {"hostname", host_name()},
            {"cpu_model", cpu_model()},
            {"cpu_vendor", m.cpu_vendor},
            {"cpu_family", m.cpu_family},
            {"cpu_model_id", m.cpu_model_id},
            {"cpu_stepping", m.cpu_stepping},
            {"cpu_isa", m.cpu_isa},
            {"cpu_count", std::to_string(m.cpu_count)},
            {"memory_bytes", std::to_string(m.memory_bytes)},
            {"kernel", m.kernel},
            {"machine_id", m.fingerprint},
            {"lp_num_threads", lp_num_threads()},
            {"env", recorded_env()},
            {"preset", opt_.preset_name},
            {"shard", opt_.shard.text()}};
  }

  RowSettings row_settings(const Planned& p) const {
    return {run_columns_, p.exp->name(),  p.res,       p.reps, p.warmup, p.policy.adaptive ? p.policy.target_ci : 0.0,
            group_index_, use_gpu_timer_, sync_passes_};
  }

  static CaseRecord new_record(const ParamSet& params, const Planned& p) {
    CaseRecord r;
    r.params = params;
    r.key = case_key(p.exp->name(), p.res, params);
    r.variant = params.has("variant") ? params.get("variant") : "";
    return r;
  }

  void prepare(Experiment& exp, Resolution res, LiveCase& c) {
    auto& rec = c.record;
    if (auto why = exp.unsupported_reason(gl_, rec.params); !why.empty()) {
      rec.fail(Status::Unsupported, why);
      return;
    }
    if (auto why = render_target_size_problem(res.width, res.height); !why.empty()) {
      rec.fail(Status::Unsupported, "render target " + why);
      return;
    }
    try {
      CaseContext cctx(*shaders_, gl_, res, rec.params.get("fault"), static_cast<unsigned>(rec.params.get_int("seed")),
                       opt_.image_stem, use_gpu_timer_, shared_.get(), &clock_);
      cctx.set_memory(current_memory_limits(gl_.is_software_renderer(), gl_.has_extension("GL_NVX_gpu_memory_info"),
                                            gl_.has_extension("GL_ATI_meminfo"), opt_.memory_limit));
      glFinish();
      auto t0 = Clock::now();
      auto before = shaders_->cache_counts();
      c.instance = exp.prepare(rec.params, cctx);
      for (const auto& [k, v] : c.instance->resolved_params()) rec.params.set(k, v);
      glFinish();
      rec.compile_ms = ms_since(t0);
      auto after = shaders_->cache_counts();
      unsigned hits = after.hits - before.hits, misses = after.misses - before.misses;
      rec.program_cache = !opt_.program_cache  ? "off"
                          : hits + misses == 0 ? ""
                          : misses == 0        ? "hit"
                          : hits == 0          ? "miss"
                                               : "partial";
      if (auto err = gl_error_text(); !err.empty()) rec.fail(Status::Error, "GL error after prepare: " + err);
    } catch (const Unsupported& e) {
      rec.fail(Status::Unsupported, e.what());
    } catch (const RenderTargetUnavailable& e) {
      rec.fail(Status::Unsupported, e.what());
    } catch (const std::exception& e) {
      rec.fail(Status::Error, e.what());
      std::fprintf(stderr, "\noitbench: %s %s: %s\n", exp.name().c_str(), rec.params.describe().c_str(), e.what());
    }
  }

  // Runs `runs` runs of the case's repetition as one sample; returns its passes per repetition, `total` (the
  // CPU clock around every run, per repetition) and whether it ran without a GL error.
  bool run_sample(LiveCase& c, PassTimer& timer, int runs, double scale, std::vector<PassSample>& samples,
                  double& total) {
    auto& rec = c.record;
    timer.begin_repetition();
    glFinish();
    auto t0 = Clock::now();
    for (int i = 0; i < runs; ++i) c.instance->run(timer);
    glFinish();
    total = ms_since(t0) * scale / runs;
    samples = per_repetition(timer.end_repetition(), runs, scale);
    if (auto err = gl_error_text(); !err.empty()) {
      rec.fail(Status::Error, "GL error during run: " + err);
      return false;
    }
    return true;
  }

  // An interleaved group in flight: its cases and what the phases below hand each other.
  struct GroupRun {
    const Planned& p;
    const GroupPlan& group;
    RowSettings settings;
    std::vector<LiveCase> live;
    PassTimer timer;
    std::vector<double> last_ms, warm_scale, scale;  // the last warm-up's time, the warm-up's and the samples' scale
    std::vector<bool> done;                          // a case whose interval reached the target stops
    StopReason why = StopReason::Continue;
    PhaseTimes overhead;  // the runner's own work for the group, shared among its cases at the end
    // One repetition as it ran: its passes and totals per nominal repetition, the size it ran at (runs,
    // scale) and the seconds it took. Each case's last warm-up, and its repetition of the round being
    // checked (its rows wait until the sizes are confirmed).
    struct Repetition {
      std::vector<PassSample> samples;
      double total = 0, scale = 0, seconds = 0;
      int runs = 0;
      bool ran = false;
    };
    std::vector<Repetition> last_warm, round;
    int rep_offset = 0;  // 1 where the last warm-up round was kept as the first timed one (raw rows' rep)
    GroupRun(const Planned& plan, const GroupPlan& g, RowSettings s, bool queries, bool sync)
        : p(plan),
          group(g),
          settings(std::move(s)),
          live(g.cases.size()),
          timer(queries, sync),
          last_ms(live.size(), 0),
          warm_scale(live.size(), 1.0),
          scale(live.size(), 1.0),
          done(live.size(), false),
          last_warm(live.size()),
          round(live.size()) {}
  };

  // Keeps the run's clock off a group's records once the group is gone.
  struct Detach {
    PhaseClock& clock;
    ~Detach() { clock.attach(nullptr, Phase::Other); }
  };

  void run_group(const Planned& p, const GroupPlan& group) {
    // Query results recorded always; the primary clock only where trusted.
    GroupRun g(p, group, row_settings(p), gl_.has_timer_query(), sync_passes_);
    const Detach detach{clock_};
    clock_.attach(&g.overhead, Phase::Other);
    prepare_group(g);
    const GpuReading gpu_start = gpu_.read();  // the clocks around the timed work (empty without NVML)
    warm_up(g);
    size_samples(g);
    timed_rounds(g);
    ++group_index_;
    if (signals_.stopped()) return;  // unfinished cases write nothing; finished rows are on disk
    finish_group(g, gpu_start, gpu_.read());
  }

  void prepare_group(GroupRun& g) {
    Experiment& exp = *g.p.exp;
    for (size_t i = 0; i < g.live.size(); ++i) {
      g.live[i].record = new_record(g.group.cases[i], g.p);
      if (!g.p.baseline.empty()) g.live[i].record.baseline = baseline_text(g.p.baseline);
      watchdog_->set_current(exp.name() + " " + g.group.cases[i].describe());
      g.live[i].record.accounted = true;
      const Charging charging(clock_, g.live[i].record.phases, Phase::Scene, g.overhead);
      prepare(exp, g.p.res, g.live[i]);
    }
    for (size_t i = 0; i < g.live.size(); ++i)
      if (g.group.baseline_of[i] >= 0)
        g.live[i].record.baseline_record = &g.live[static_cast<size_t>(g.group.baseline_of[i])].record;
  }

  // Warm-up, interleaved across the group: A B C A B C ...; the last one sizes the samples.
  // Scalable work warms up on one unit (one draw of occupancy's 64: the JIT, not 64 times the work),
  // its time scaled to the nominal repetition for sizing; warmup_ms keeps what the one unit took.
  void warm_up(GroupRun& g) {
    const Planned& p = g.p;
    auto& live = g.live;
    for (size_t i = 0; i < live.size(); ++i)
      if (live[i].active() && p.policy.max_sample_ms > 0)
        if (const int nominal = live[i].instance->nominal_units(); nominal > 1) {
          live[i].instance->set_units(1);
          g.warm_scale[i] = nominal;
        }
    for (int r = -p.warmup; r < 0 && !signals_.stopped(); ++r) {
      for (size_t i = 0; i < live.size(); ++i) {
        auto& c = live[i];
        if (!c.active() || signals_.stopped()) continue;
        watchdog_->set_current(p.exp->name() + " " + c.record.params.describe());
        try {
          std::vector<PassSample> samples;
          double total = 0;
          const double before = c.record.phases[Phase::Warmup];
          {
            const Charging charging(clock_, c.record.phases, Phase::Warmup, g.overhead);
            if (!run_sample(c, g.timer, 1, g.warm_scale[i], samples, total)) continue;
          }
          if (r == -p.warmup) c.record.warmup_ms = total / g.warm_scale[i];
          g.last_ms[i] = total;
          g.last_warm[i] = {
              std::move(samples), total, g.warm_scale[i], c.record.phases[Phase::Warmup] - before, 1, true};
        } catch (const std::exception& e) {
          c.record.fail(Status::Error, std::string("run: ") + e.what());
        }
      }
      watchdog_->heartbeat();
      progress_->report(p.exp->name(), cases_done_, live.size(), r + p.warmup + 1, steps(p));
    }
  }

  static int steps(const Planned& p) { return p.warmup + (p.policy.adaptive ? p.policy.max_reps : p.reps); }

  // Sample sizes: fewer units of scalable work where a repetition is long, more runs where it is short.
  // The warm-up may have held the JIT: the first timed round checks the size again (check_sizes).
  void size_samples(GroupRun& g) {
    const SamplingPolicy& policy = g.p.policy;
    for (size_t i = 0; i < g.live.size() && !signals_.stopped(); ++i) {
      auto& c = g.live[i];
      if (!c.active()) continue;
      auto& rec = c.record;
      try {
        if (const int nominal = c.instance->nominal_units(); nominal > 0) {
          rec.sample_units = units_per_run(g.last_ms[i], nominal, policy.min_sample_ms, policy.max_sample_ms);
          c.instance->set_units(rec.sample_units);
          g.scale[i] = static_cast<double>(nominal) / rec.sample_units;
        }
        const double rep_ms = g.last_ms[i] / g.scale[i];  // one run at the units it will do
        rec.sample_runs = runs_per_sample(rep_ms, policy.min_sample_ms);
      } catch (const std::exception& e) {
        rec.fail(Status::Error, std::string("run: ") + e.what());
      }
    }
  }

  // Timed repetitions, interleaved, until the stopping rule says the group has enough. A case whose own
  // interval reached the target stops (stop=target) while the others go on; a baseline goes on while a
  // case it pairs with does (sampling.hpp: step_group).
  // The first rounds check the sample sizes again: a round after a JIT-laden warm-up (or after a resize
  // chosen from such a round) can still be slow, so each check sizes from the round just run, until a
  // round needs no resize or kMaxSizeChecks rounds were taken as warm-up.
  void timed_rounds(GroupRun& g) {
    constexpr int kMaxSizeChecks = 4;
    auto& live = g.live;
    auto timed_start = Clock::now();  // restarted when a round is taken as warm-up
    int size_checks = 0;
    bool checked_size = false;
    for (int r = 0; !signals_.stopped(); ++r) {
      std::vector<std::vector<double>> totals(live.size());
      bool any_active = false;
      for (size_t i = 0; i < live.size(); ++i)
        if (live[i].active()) {
          any_active = true;
          if (live[i].record.cpu.count("total")) totals[i] = live[i].record.cpu.at("total");
        }
      if (!any_active) break;
      g.why = step_group(g.p.policy, totals, g.group.baseline_of, ms_since(timed_start) / 1000.0, g.done);
      if (g.why != StopReason::Continue) break;
      std::vector<double> sampled(live.size());  // each case's timed seconds before this round
      for (size_t i = 0; i < live.size(); ++i) sampled[i] = live[i].record.phases[Phase::Samples];
      for (auto& rep : g.round) rep.ran = false;
      const std::vector<char> ran = timed_round(g, r, !checked_size);
      probe_memory(g, ran);
      if (!checked_size) {
        const bool resized = check_sizes(g);
        const bool first_check = size_checks == 0;
        checked_size = !resized || ++size_checks >= kMaxSizeChecks;
        if (resized) {
          for (size_t i = 0; i < live.size(); ++i) {  // the round was warm-up, in the account too
            PhaseTimes& t = live[i].record.phases;
            t[Phase::Warmup] += t[Phase::Samples] - sampled[i];
            t[Phase::Samples] = sampled[i];
          }
          for (auto& c : live) {
            c.record.cpu.clear();
            c.record.gpu.clear();
            c.record.mem_ns.clear();
          }
          g.done.assign(live.size(), false);
          timed_start = Clock::now();  // a round taken as warm-up is not timed work
          r = -1;                      // the next round is the first timed one again
        } else {
          if (first_check) keep_settled_warmup(g);
          write_checked_round(g, r);
        }
      }
      watchdog_->heartbeat();
      progress_->report(g.p.exp->name(), cases_done_, live.size(), r + g.p.warmup + 1, steps(g.p));
    }
  }

  // The host's memory latency after a round (core/memory_probe.hpp), in the record of every case that ran in
  // it: about a millisecond between rounds, outside every case's timed samples (the time account's `other`).
  void probe_memory(GroupRun& g, const std::vector<char>& ran) {
    if (!opt_.mem_probe || mem_probe_failed_ || std::find(ran.begin(), ran.end(), 1) == ran.end()) return;
    if (!mem_probe_) try {
        mem_probe_ = std::make_unique<MemoryProbe>(static_cast<size_t>(opt_.mem_probe_mib) << 20);
      } catch (const std::exception& e) {  // its buffer refused (RLIMIT_AS, RLIMIT_DATA): rows without it
        mem_probe_failed_ = true;
        std::fprintf(stderr, "oitbench: warning: no memory probe (host_mem_ns stays empty): %s\n", e.what());
        return;
      }
    const double ns = mem_probe_->latency_ns();
    for (size_t i = 0; i < g.live.size(); ++i)
      if (ran[i]) g.live[i].record.mem_ns.push_back(ns);
  }

  // One timed round over the group's running cases; raw rows go to the file, or, while the round's sizes
  // are not confirmed (`checking`), wait in g.round with the repetitions (write_checked_round). Returns
  // which cases ran a repetition.
  std::vector<char> timed_round(GroupRun& g, int r, bool checking) {
    std::vector<char> ran(g.live.size(), 0);
    for (size_t i = 0; i < g.live.size(); ++i) {
      auto& c = g.live[i];
      if (!c.active() || g.done[i] || signals_.stopped()) continue;
      auto& rec = c.record;
      watchdog_->set_current(g.p.exp->name() + " " + rec.params.describe());
      try {
        std::vector<PassSample> samples;
        double total = 0;
        const double before = rec.phases[Phase::Samples];
        {
          const Charging charging(clock_, rec.phases, Phase::Samples, g.overhead);
          if (!run_sample(c, g.timer, rec.sample_runs, g.scale[i], samples, total)) continue;
        }
        double gpu_total = rec.add_repetition(samples, total);
        ran[i] = 1;
        if (checking)
          g.round[i] = {std::move(samples), total, g.scale[i], rec.phases[Phase::Samples] - before,
                        rec.sample_runs,    true};
        else if (raw_writer_)
          write(*raw_writer_, raw_rows(g.settings, rec, r + g.rep_offset, samples, total, gpu_total));
      } catch (const std::exception& e) {
        rec.fail(Status::Error, std::string("run: ") + e.what());
      }
    }
    return ran;
  }

  // The warm-up ends when timings settle, not after a fixed count: where the first timed round shows that
  // every running case's last warm-up repetition had settled (it ran at the size of the samples and took
  // at most --warmup-settle (10 %) longer than the case's first timed repetition: warmup_settled, on the
  // CPU clock and, where it is primary, the GPU's), the group's last warm-up round counts as its first
  // timed round. All cases or none, so paired rounds stay paired and the raw file's rounds stay rounds. A
  // warm-up that held the JIT (llvmpipe compiles at the first draw) or another first-time cost stays one.
  void keep_settled_warmup(GroupRun& g) {
    const double tolerance = g.p.policy.warmup_settle;
    if (!(tolerance > 0)) return;
    auto gpu_total = [](const std::vector<PassSample>& samples) {
      double t = samples.empty() ? -1 : 0;
      for (const auto& s : samples) t = (t < 0 || s.gpu_ms < 0) ? -1 : t + s.gpu_ms;
      return t;
    };
    bool any = false;
    for (size_t i = 0; i < g.live.size(); ++i) {
      if (!g.live[i].active()) continue;
      const auto &w = g.last_warm[i], &t = g.round[i];
      if (!w.ran || !t.ran || w.runs != t.runs || w.scale != t.scale || !warmup_settled(w.total, t.total, tolerance))
        return;
      if (use_gpu_timer_ && !warmup_settled(gpu_total(w.samples), gpu_total(t.samples), tolerance)) return;
      any = true;
    }
    if (!any) return;
    for (size_t i = 0; i < g.live.size(); ++i) {
      auto& rec = g.live[i].record;
      if (!g.live[i].active()) continue;
      const auto &w = g.last_warm[i], &t = g.round[i];
      rec.cpu.clear();
      rec.gpu.clear();
      rec.add_repetition(w.samples, w.total);
      rec.add_repetition(t.samples, t.total);
      rec.phases[Phase::Warmup] -= w.seconds;  // its time was a sample's, in the account too
      rec.phases[Phase::Samples] += w.seconds;
      rec.warmup_kept = 1;
    }
    g.rep_offset = 1;
  }

  // The raw rows of a checked round whose sizes stood (and of the warm-up kept before it).
  void write_checked_round(GroupRun& g, int r) {
    if (!raw_writer_) return;
    for (size_t i = 0; i < g.live.size(); ++i) {
      const auto& rec = g.live[i].record;
      const auto &w = g.last_warm[i], &t = g.round[i];
      if (!t.ran) continue;
      std::vector<Row> rows;
      if (rec.warmup_kept) {
        rows = raw_rows(g.settings, rec, r, w.samples, w.total, rec.gpu.at("total").at(0));
        auto more = raw_rows(g.settings, rec, r + 1, t.samples, t.total, rec.gpu.at("total").at(1));
        rows.insert(rows.end(), more.begin(), more.end());
      } else {
        rows = raw_rows(g.settings, rec, r, t.samples, t.total, rec.gpu.at("total").back());
      }
      write(*raw_writer_, rows);
    }
  }

  // After a round whose sizes are not confirmed: a sample shorter than half of --min-sample-ms was sized
  // from a warm-up that held the JIT; size it from this round. Returns whether any case was resized (the
  // round is then one more warm-up, for every case of the group alike).
  bool check_sizes(GroupRun& g) {
    const SamplingPolicy& policy = g.p.policy;
    bool resized = false;
    for (size_t i = 0; i < g.live.size(); ++i) {
      auto& rec = g.live[i].record;
      if (!g.live[i].active() || !rec.cpu.count("total") || rec.cpu.at("total").empty()) continue;
      const double rep_ms = rec.cpu.at("total").back();  // per nominal repetition
      if (const int nominal = g.live[i].instance->nominal_units(); nominal > 0) {
        // Units chosen from a JIT-laden warm-up may be far too few: choose them again from this round.
        const int units = units_per_run(rep_ms, nominal, policy.min_sample_ms, policy.max_sample_ms);
        if (units > rec.sample_units * 3 / 2 || units * 3 / 2 < rec.sample_units) {
          rec.sample_units = units;
          g.live[i].instance->set_units(units);
          g.scale[i] = static_cast<double>(nominal) / units;
          rec.sample_runs = runs_per_sample(rep_ms / g.scale[i], policy.min_sample_ms);
          resized = true;
          continue;
        }
      }
      const double sample_ms = rep_ms / g.scale[i] * rec.sample_runs;
      if (sample_ms >= policy.min_sample_ms / 2) continue;
      rec.sample_runs = runs_per_sample(sample_ms / rec.sample_runs, policy.min_sample_ms);
      resized = true;
    }
    return resized;
  }

  // Validation, notes and rows, after every case of the group ran: a speedup needs its baseline's status.
  void finish_group(GroupRun& g, const GpuReading& gpu_start, const GpuReading& gpu_end) {
    RowSettings summary = g.settings;
    for (const auto& [k, v] : gpu_state_columns(gpu_start, gpu_end)) summary.run[k] = v;
    const std::string clock_note = clock_change_note(gpu_start, gpu_end);
    for (size_t i = 0; i < g.live.size(); ++i) {
      auto& c = g.live[i];
      auto& rec = c.record;
      if (c.instance) {
        const Charging charging(clock_, rec.phases, Phase::Validate, g.overhead);
        for (const auto& [k, v] : c.instance->metrics()) rec.metrics[k] = v;
        if (c.active()) validate(c);
      }
      // The cases that ran while the clocks moved say so (those that never ran have nothing to qualify).
      if (!clock_note.empty() && (rec.status == Status::Ok || rec.status == Status::Invalid)) rec.add_note(clock_note);
      if (rec.status == Status::Ok && rec.cpu.count("total")) {
        const StopReason case_why = g.done[i] ? StopReason::Target : g.why;
        rec.stop = stop_reason_name(case_why);
        if (auto note = ci_note(g.p.policy, rec.cpu.at("total"), case_why); !note.empty()) rec.add_note(note);
      }
    }
    share_overhead(g);
    for (size_t i = 0; i < g.live.size(); ++i) {
      if (!g.group.shadow[i]) finish_case(summary, g.live[i].record);
      g.live[i].instance.reset();
    }
  }

  // The group's own work so far, shared equally among its cases (their `other`), so that the cases'
  // wall times add up to the group's; then every case's phases into the run's account. A shadow (a
  // baseline run again to pair with this group's cases, which writes no row) shares its phases, phase by
  // phase, among the cases that write rows, so that the rows add up to the run too. Writing the rows is
  // the run's, timed apart (finish_case).
  void share_overhead(GroupRun& g) {
    clock_.attach(nullptr, Phase::Other);
    const double share = g.overhead.total() / static_cast<double>(std::max<size_t>(1, g.live.size()));
    PhaseTimes shadows;
    size_t writers = 0;
    for (size_t i = 0; i < g.live.size(); ++i) {
      g.live[i].record.phases[Phase::Other] += share;
      if (g.group.shadow[i])
        shadows += g.live[i].record.phases;
      else
        ++writers;
    }
    for (size_t i = 0; i < g.live.size(); ++i) {
      auto& phases = g.live[i].record.phases;
      if (writers > 0 && g.group.shadow[i]) phases = PhaseTimes{};
      if (writers > 0 && !g.group.shadow[i])
        for (size_t k = 0; k < kPhaseCount; ++k) phases.seconds[k] += shadows.seconds[k] / static_cast<double>(writers);
      account_.cases += phases;
    }
  }

  static void validate(LiveCase& c) {
    auto& rec = c.record;
    try {
      Validation v = c.instance->validate();
      for (const auto& [k, val] : v.metrics) rec.metrics[k] = val;
      if (v.valid)
        rec.note = v.reason;
      else
        rec.fail(Status::Invalid, v.reason);
    } catch (const std::exception& e) {
      rec.fail(Status::Error, std::string("validate: ") + e.what());
    }
  }

  void write(CsvWriter& w, const std::vector<Row>& rows) {
    std::lock_guard lock(mutex_);
    for (const auto& row : rows) w.write(row);
  }

  void finish_case(const RowSettings& settings, const CaseRecord& rec) {
    const auto rows = summary_rows(settings, rec);
    const auto t0 = Clock::now();
    write(*writer_, rows);
    account_.write_s += seconds_since(t0);
    for (const auto& row : rows)
      if (row.count("pass") && row.at("pass") == "total") add_outcome(rec.key, row);
    ++counts_[rec.status];
    ++cases_done_;
  }

  // --dry-run: the plan this driver would run (its sizes and grids), request by request on stdout, and
  // nothing else: no CSV is opened, no case is built or run. With --shard, this shard's cases.
  int dry_run(const std::vector<RunRequest>& requests) {
    const std::vector<Planned> plan = make_plan(registry_, requests, opt_, !gl_.is_software_renderer());
    size_t total = 0;
    for (const auto& p : plan) {
      const size_t cases = UnitStream({p}, opt_, opt_.shard).count_rows();
      total += cases;
      std::printf(
          "plan: %s %dx%d cases=%zu reps=%s warmup=%d\n", p.exp->name().c_str(), p.res.width, p.res.height, cases,
          p.policy.adaptive
              ? ("auto (" + std::to_string(p.policy.min_reps()) + "-" + std::to_string(p.policy.max_reps) + ")").c_str()
              : std::to_string(p.reps).c_str(),
          p.warmup);
    }
    std::printf("dry run: %zu case(s) on %s; nothing was run\n", total, gl_.renderer.c_str());
    return 0;
  }

  // The --expect patterns that match no case of the whole grid (every shard's), walked key by key until
  // every pattern matched one.
  void note_grid(const std::vector<Planned>& plan) {
    if (expected_.empty()) return;
    unmatched_ = unmatched_patterns(expected_, [&](const std::function<bool(const std::string&)>& visit) {
      bool more = true;
      for (const auto& p : plan) {
        p.grid->for_each([&](const ParamSet& c) { return more = visit(case_key(p.exp->name(), p.res, c)); });
        if (!more) return;
      }
    });
  }

  // A case's outcome from its total row (--expect, --junit, --write-expect; without them none is kept, so
  // a run of millions of cases does not grow with them).
  void add_outcome(const std::string& key, const Row& row) {
    if (!keep_outcomes_) return;
    Outcome o;
    o.key = key;
    o.experiment = row.count("experiment") ? row.at("experiment") : "";
    for (Status s : kAllStatuses)
      if (row.count("status") && row.at("status") == status_name(s)) o.status = s;
    o.reason = row.count("reason") ? row.at("reason") : "";
    if (row.count("median_ms") && !row.at("median_ms").empty()) try {
        o.median_ms = std::stod(row.at("median_ms"));
      } catch (const std::exception&) {
      }
    outcomes_.push_back(std::move(o));
  }

 public:
  const std::vector<Outcome>& outcomes() const { return outcomes_; }
  const std::vector<std::string>& unmatched() const { return unmatched_; }
  const Row& run_columns() const { return run_columns_; }

 private:
  // A case in a child process (`oitbench run EXP --set k=v ... --isolate never`), killed by the
  // watchdog when it exceeds --timeout: spinlock variants can hang a real GPU.
  void run_isolated(const Planned& p, const ParamSet& params) {
    Experiment& exp = *p.exp;
    watchdog_->set_current(exp.name() + " " + params.describe());
    const std::string dir = make_case_dir();  // removes folders that killed runs left behind
    std::string out = dir + "/case.csv", raw = dir + "/raw.csv";
    std::vector<std::string> args = {"/proc/self/exe",
                                     "run",
                                     exp.name(),
                                     "--out",
                                     out,
                                     "--isolate",
                                     "never",
                                     "--no-progress",
                                     "--isolated-child",
                                     "--backend",
                                     opt_.context.backend,
                                     "--driver",
                                     opt_.context.driver,
                                     "--device",
                                     std::to_string(opt_.context.device),
                                     "--resolution",
                                     std::to_string(p.res.width) + "x" + std::to_string(p.res.height),
                                     "--warmup",
                                     std::to_string(p.warmup),
                                     "--timer",
                                     opt_.timer,
                                     "--shaders",
                                     opt_.shader_root};
    if (p.policy.adaptive)
      args.insert(args.end(), {"--target-ci", fmt_number(p.policy.target_ci * 100), "--max-reps",
                               std::to_string(p.policy.max_reps), "--max-case-s", fmt_number(p.policy.max_case_s)});
    else
      args.insert(args.end(), {"--reps", std::to_string(p.reps)});
    args.insert(args.end(),
                {"--min-sample-ms", fmt_number(p.policy.min_sample_ms), "--max-sample-ms",
                 fmt_number(p.policy.max_sample_ms), "--warmup-settle", fmt_number(p.policy.warmup_settle * 100)});
    if (!opt_.preset_name.empty()) args.insert(args.end(), {"--preset-name", opt_.preset_name});
    args.insert(args.end(), {"--run-id", run_id_});
    for (const auto& [k, v] : opt_.tags) args.insert(args.end(), {"--tag", k + "=" + v});
    if (raw_writer_) args.insert(args.end(), {"--raw", raw});
    if (!opt_.interleave) args.push_back("--no-interleave");
    if (!opt_.program_cache) args.push_back("--no-program-cache");
    if (opt_.sync_passes) args.push_back("--sync-passes");
    if (!opt_.mem_probe) args.push_back("--no-mem-probe");
    args.insert(args.end(), {"--mem-probe-mib", std::to_string(opt_.mem_probe_mib)});
    if (opt_.memory_limit) args.insert(args.end(), {"--memory-limit", std::to_string(*opt_.memory_limit)});
    // Only what the case uses: the child's grid gives the rest their defaults and marks them unused.
    for (const auto& [k, v] : params.used_values()) args.insert(args.end(), {"--set", k + "=" + v});
    const auto started = Clock::now();
    const double accounted = account_.cases.total();
    auto outcome = run_child(
        args, opt_.timeout_s, [this] { return signals_.stopped(); }, [this] { watchdog_->heartbeat(); });
    watchdog_->heartbeat();
    bool copied = false;
    if (outcome.kind == ChildOutcome::Kind::Exited || outcome.kind == ChildOutcome::Kind::Signalled)
      copied = copy_rows(out, *writer_, case_key(exp.name(), p.res, params)) > 0;
    if (copied && raw_writer_) copy_rows(raw, *raw_writer_, "");
    if (!copied && outcome.kind != ChildOutcome::Kind::Stopped) {
      CaseRecord rec = new_record(params, p);
      switch (outcome.kind) {
        case ChildOutcome::Kind::TimedOut:
          rec.fail(Status::Timeout, "killed by the watchdog after " + fmt_number(opt_.timeout_s, 3) + " s (--timeout)");
          break;
        case ChildOutcome::Kind::Signalled:
          rec.fail(Status::Error, "the case's process died with signal " + std::to_string(outcome.code));
          break;
        default:
          rec.fail(Status::Error,
                   "the case's process exited with code " + std::to_string(outcome.code) + " and no rows");
      }
      finish_case(row_settings(p), rec);
    }
    std::filesystem::remove_all(dir);
    // The child's life apart from its case: process and context start, its writing.
    account_.child_start_s += std::max(0.0, seconds_since(started) - (account_.cases.total() - accounted));
    progress_->report(exp.name(), cases_done_, 0, 1, 1);
  }

  // `key`: the case's key, whose summary rows these are (empty: raw rows, not counted).
  size_t copy_rows(const std::string& path, CsvWriter& into, const std::string& key) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return 0;
    std::stringstream ss;
    ss << in.rdbuf();
    auto rows = csv_parse(ss.str());
    if (rows.size() < 2) return 0;
    const auto& header = rows[0];
    std::lock_guard lock(mutex_);
    for (size_t i = 1; i < rows.size(); ++i) {
      Row row;
      for (size_t j = 0; j < header.size() && j < rows[i].size(); ++j) row[header[j]] = rows[i][j];
      row["shard"] = opt_.shard.text();  // the child ran one case of this shard
      into.write(row);
      if (!key.empty() && row["pass"] == "total") {
        add_outcome(key, row);
        account_.cases += phases_of(row);
        for (Status s : kAllStatuses)
          if (row["status"] == status_name(s)) ++counts_[s];
        ++cases_done_;
      }
    }
    return rows.size() - 1;
  }

  // A copied row's time account (none where its columns are empty).
  static PhaseTimes phases_of(const Row& row) {
    PhaseTimes t;
    for (Phase ph : kAllPhases) {
      auto it = row.find(phase_column(ph));
      if (it == row.end() || it->second.empty()) continue;
      try {
        t[ph] = std::stod(it->second);
      } catch (const std::exception&) {
      }
    }
    return t;
  }

  Registry& registry_;
  const RunOptions& opt_;
  const std::vector<Expectation>& expected_;
  const std::string run_id_;
  const bool keep_outcomes_;
  SignalGuard signals_;
  std::unique_ptr<Context> ctx_;
  GlInfo gl_;
  GpuMonitor gpu_;  // NVML where the GL driver is NVIDIA's; inactive elsewhere
  std::unique_ptr<ShaderLibrary> shaders_;
  // Declared after the context: destroyed first, while its GL objects can still be deleted.
  std::unique_ptr<SharedCache> shared_ = std::make_unique<SharedCache>();
  bool use_gpu_timer_ = false, sync_passes_ = true;
  std::unique_ptr<CsvWriter> writer_, raw_writer_;
  Row run_columns_;
  std::map<Status, int> counts_;
  std::vector<Outcome> outcomes_;       // every case this run wrote, in order
  std::vector<std::string> unmatched_;  // --expect patterns that match no case of the grid
  size_t cases_done_ = 0;
  int group_index_ = 0;  // interleaved groups run so far (the raw rows' group)
  std::unique_ptr<Progress> progress_;
  std::unique_ptr<Watchdog> watchdog_;
  std::mutex mutex_;
  PhaseClock clock_;    // the time account's clock: charges the case being worked on (core/phases.hpp)
  RunAccount account_;  // the run's: its start, writing, children, every case's phases
  std::unique_ptr<MemoryProbe> mem_probe_;  // built at the first timed round that probes (--no-mem-probe: never)
  bool mem_probe_failed_ = false;           // its buffer could not be allocated: warned once, no probes
};

}  // namespace

RunSize resolve_run_size(const RunRequest& r, const Experiment& e, const RunOptions& opt, bool hardware_driver) {
  const bool quick = opt.quick || r.quick;
  const HardwareSizes hw = hardware_driver && r.hardware ? *r.hardware : HardwareSizes{};
  RunSize s;
  s.hardware_sizes = (!opt.resolution && hw.resolution) || (!opt.reps_given && hw.reps) ||
                     (!opt.warmup_given && hw.warmup) || !hw.set.empty();
  s.resolution = opt.resolution  ? *opt.resolution
                 : hw.resolution ? *hw.resolution
                 : r.resolution  ? *r.resolution
                 : quick         ? e.quick_resolution()
                                 : e.default_resolution();
  s.reps = opt.reps_given ? opt.reps : hw.reps ? *hw.reps : r.reps.value_or(quick ? std::min(opt.reps, 3) : opt.reps);
  // The stopping rule decides unless a count is given: --reps, the entry's reps, a --quick grid, or
  // a caller that did not ask for it (RunOptions::sampling.adaptive).
  s.fixed_reps = !opt.sampling.adaptive || opt.reps_given || hw.reps || r.reps || quick;
  s.warmup = opt.warmup_given ? opt.warmup : hw.warmup ? *hw.warmup : r.warmup.value_or(opt.warmup);
  return s;
}

namespace {
// An error of a preset entry's hardware set: check_requests names the set's own place, not the entry's.
class HardwareSetError : public UsageError {
 public:
  using UsageError::UsageError;
};

// A baseline no case of the grid has would name a case that never runs: refused.
void check_baseline_in_grid(const std::map<std::string, std::string>& baseline, const CaseGrid& grid) {
  if (baseline.empty() || grid.has_case_with(baseline)) return;
  throw UsageError("the baseline " + baseline_text(baseline) +
                   " is not a case of the grid, so it would never run: add its values to the grid (e.g. --set " +
                   baseline.begin()->first + "=...," + baseline.begin()->second + ") or choose another baseline");
}

// One request against the registry; returns its grids (a software renderer's, and a hardware driver's where
// it has a hardware set), checked but not counted.
std::vector<CaseGrid> check_request(const Registry& registry, const RunRequest& r, bool quick, size_t max_cases) {
  const Experiment* e = registry.find(r.experiment);
  if (!e)
    throw UsageError("unknown experiment '" + r.experiment + "'; valid experiments: " + registry.names() + ", all");
  auto specs = registry.params_of(*e);
  for (const auto& [name, value] : r.baseline) {
    auto it = std::find_if(specs.begin(), specs.end(), [&](const ParamSpec& s) { return s.name == name; });
    if (it == specs.end())
      throw UsageError("experiment '" + e->name() + "': the baseline names no parameter '" + name + "'");
    try {
      it->check(value, e->name());
    } catch (const UsageError& err) {
      throw UsageError("the baseline " + name + "=" + value + ": " + err.what());
    }
  }
  // The grid on a software renderer and, where the entry has a hardware "set", the one on hardware: both
  // must be valid wherever the check runs.
  std::vector<CaseGrid> grids;
  for (bool hardware : {false, true}) {
    if (hardware && (!r.hardware || r.hardware->set.empty())) break;
    const auto overrides = request_overrides(r, hardware);
    for (const auto& [name, values] : overrides) {
      auto it = std::find_if(specs.begin(), specs.end(), [&](const ParamSpec& s) { return s.name == name; });
      if (it == specs.end()) {
        std::string valid;
        for (const auto& s : specs) valid += (valid.empty() ? "" : ", ") + s.name;
        const std::string what = "experiment '" + e->name() + "' has no parameter '" + name + "'";
        if (hardware && r.hardware->set.count(name))
          throw HardwareSetError(what + " (in its hardware set); valid parameters: " + valid);
        throw UsageError(what + "; valid parameters: " + valid);
      }
      try {
        for (const auto& v : values) it->check(v, e->name());
      } catch (const UsageError& err) {
        if (!hardware || !r.hardware->set.count(name)) throw;
        throw HardwareSetError(err.what());
      }
    }
    try {
      // a grid too large, a scoped --set that no case uses, a case the experiment's data rules out: the
      // grid is walked, never built (core/grid.hpp)
      CaseGrid grid(specs, overrides, quick || r.quick, max_cases);
      grid.check_overrides_apply();
      if (const auto names = e->checked_params(); !names.empty()) e->check_cases(grid.distinct(names));
      check_baseline_in_grid(r.baseline, grid);
      grids.push_back(std::move(grid));
    } catch (const UsageError& err) {
      // The software grid passed: on hardware, what differs is the hardware set.
      if (hardware) throw HardwareSetError("experiment '" + e->name() + "' on a hardware driver: " + err.what());
      throw UsageError("experiment '" + e->name() + "': " + err.what());
    }
  }
  return grids;
}

// The most cases of a request's grids: `exact` counts them (a walk), else the products bound them.
size_t most_cases(const std::vector<CaseGrid>& grids, bool exact) {
  size_t most = 0;
  for (const auto& g : grids) most = std::max(most, exact ? g.count() : static_cast<size_t>(g.raw_size()));
  return most;
}
}  // namespace

std::map<std::string, std::vector<std::string>> request_overrides(const RunRequest& r, bool hardware_driver) {
  auto o = r.overrides;
  if (hardware_driver && r.hardware)
    for (const auto& [k, v] : r.hardware->set) o[k] = v;
  return o;
}

void check_requests(const Registry& registry, const std::vector<RunRequest>& requests, bool quick, size_t max_cases) {
  if (requests.empty()) throw UsageError("nothing to run; experiments: " + registry.names());
  std::vector<std::vector<CaseGrid>> grids;
  size_t bound = 0;  // the products: counting (a walk of every number) only where they exceed max_cases
  for (const auto& r : requests) {
    try {
      grids.push_back(check_request(registry, r, quick, max_cases));
    } catch (const HardwareSetError& e) {
      const std::string at = r.hardware && !r.hardware->origin.empty() ? r.hardware->origin
                             : r.origin.empty()                        ? std::string("hardware.set")
                                                                       : r.origin + ": hardware.set";
      throw UsageError(at + ": " + e.what());
    } catch (const UsageError& e) {
      if (r.origin.empty()) throw;
      throw UsageError(r.origin + ": " + e.what());
    }
    bound += most_cases(grids.back(), false);
    if (bound <= max_cases) continue;
    size_t total = 0;
    for (const auto& g : grids) total += most_cases(g, true);
    if (total > max_cases)
      throw UsageError("the run has " + std::to_string(total) + " cases or more, more than " +
                       std::to_string(max_cases) + "; narrow a --set list or the experiments, or raise --max-cases");
  }
}

int run_experiments(Registry& registry, const std::vector<RunRequest>& requests, const RunOptions& options) {
  check_requests(registry, requests, options.quick, options.max_cases);
  // A malformed baseline is a usage error before any work.
  const std::vector<Expectation> baseline =
      options.expect.empty() ? std::vector<Expectation>{} : load_expectations(options.expect);
  Runner runner(registry, options, baseline);
  const int code = runner.run(requests);
  return report_outcomes(options, baseline, runner.outcomes(), runner.unmatched(), runner.run_columns(), code);
}

std::string default_shader_root() { return data_dir("shaders"); }

}  // namespace oitbench
