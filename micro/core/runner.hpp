#pragma once
// Runs experiments: expands grids, interleaves the cases' repetitions, validates, writes rows.
// The pieces live beside it: rows.hpp (statistics into rows), provenance.hpp (what a row records
// about the run), isolation.hpp (child processes, the watchdog), progress.hpp (the progress line).
#include <chrono>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/provenance.hpp"
#include "core/registry.hpp"
#include "core/sampling.hpp"
#include "core/schema.hpp"
#include "core/shard.hpp"

namespace oitbench {

// A preset entry's sizes for hardware drivers ("hardware": {...}): each one given replaces the entry's own
// where the renderer is not a software one (GlInfo::is_software_renderer()).
struct HardwareSizes {
  std::optional<Resolution> resolution;
  std::optional<int> reps, warmup;
  // Parameter lists that replace the entry's own on hardware drivers (a grid a software renderer cannot
  // afford, e.g. 64 peeled layers of 12.76 M triangles); a --set of the same name replaces both.
  std::map<std::string, std::vector<std::string>> set{};
  std::string origin{};  // where its "set" is, "presets/x.json:7:20: runs[0].hardware.set": what its errors name
};

// One experiment to run, from the command line or from one entry of a preset.
struct RunRequest {
  std::string experiment;
  std::map<std::string, std::vector<std::string>> overrides;  // --set NAME=V1,V2
  std::optional<Resolution> resolution;
  std::optional<int> reps, warmup;
  bool quick = false;  // this request uses the experiment's --quick grid and resolution
  std::optional<HardwareSizes> hardware{};
  std::string origin{};  // a preset's entry, "presets/x.json:3:5: runs[0]": what its errors name
  // The case each speedup divides by (a preset's "baseline", --baseline NAME=VALUE): it runs in every
  // interleaved group of the cases it is the baseline of (core/groups.hpp).
  std::map<std::string, std::string> baseline{};
};

// The request's parameter lists on a hardware driver (its hardware "set" over its own) or elsewhere.
std::map<std::string, std::vector<std::string>> request_overrides(const RunRequest& r, bool hardware_driver);

struct RunOptions {
  ContextOptions context;
  std::optional<Resolution> resolution;  // overrides every request's and the experiments' defaults
  int reps = 5, warmup = 1;
  bool reps_given = false, warmup_given = false;
  // Sample sizes and the stopping rule (--min-sample-ms, --max-sample-ms, --target-ci, --max-reps,
  // --max-case-s). `adaptive` is the command line's default; a caller that leaves it false gets `reps`.
  SamplingPolicy sampling{};
  bool quick = false;
  std::string out = "-";
  std::string raw;             // --raw: every repetition as a row
  std::string timer = "auto";  // auto | cpu | gpu
  bool sync_passes = false;    // glFinish around every pass on hardware drivers too (always on software ones)
  bool mem_probe = true;       // the host's memory latency between timed rounds (host_mem_ns; core/memory_probe.hpp)
  int mem_probe_mib = 64;      // --mem-probe-mib: the chase's buffer
  bool interleave = true;
  std::string isolate = "auto";      // auto (hang-prone experiments) | always | never
  double timeout_s = 600;            // per case, watchdog
  size_t max_cases = kMaxGridCases;  // --max-cases: the grid's bound, checked before anything is built
  bool progress = true;
  bool dry_run = false;                     // --dry-run: print the plan (requests, sizes, case counts) and run nothing
  std::string preset_name;                  // recorded in each row
  std::string run_id;                       // the run's UUID (an isolated child's: its parent's); empty: a new one
  std::map<std::string, std::string> tags;  // --tag KEY=VALUE, in the tags column
  ShardSpec shard;                          // --shard: this shard's units only (core/plan.hpp); recorded in each row
  // Fleets and CI (core/outcomes.hpp): the expected-status baseline, where to write the one this run
  // would expect, the JUnit report; empty: none.
  std::string expect, write_expect, junit;
  std::string shader_root;      // where shaders/ lives
  bool program_cache = true;    // reuse linked programs (glGetProgramBinary) across runs
  bool isolated_child = false;  // this process runs one case for a parent: no summary line
  std::string image_stem;       // render: where a case writes its images (CaseContext::image_stem)
  // When the run began (the options are made first thing): its time account's start and wall time.
  std::chrono::steady_clock::time_point started = std::chrono::steady_clock::now();
  // --memory-limit: replaces the CPU limit a case's memory estimate is held against (core/memory_budget.hpp)
  std::optional<unsigned long long> memory_limit;
};

// The size a request runs at: the command line's --resolution/--reps/--warmup first; then, on a hardware
// driver, the request's `hardware` sizes; then the request's own; then the experiment's (--quick) defaults.
struct RunSize {
  Resolution resolution;
  int reps = 0, warmup = 0;
  bool fixed_reps = true;       // reps is the count; false: the stopping rule decides
  bool hardware_sizes = false;  // a value of the request's `hardware` entry was used
};
RunSize resolve_run_size(const RunRequest& request, const Experiment& experiment, const RunOptions& options,
                         bool hardware_driver);

// Validates the requests against the registry and their grids (throws UsageError listing the valid
// names); `quick`: every request uses its experiment's --quick grid.
// `max_cases`: the most cases all requests together may have (--max-cases).
void check_requests(const Registry& registry, const std::vector<RunRequest>& requests, bool quick = false,
                    size_t max_cases = kMaxGridCases);

// Returns the process exit code: 0 finished, 1 errors or timeouts or interrupted (130), 3 nothing ran (unsupported);
// with --expect, 0 when every outcome was expected, 4 when one was not (130 interrupted stays).
int run_experiments(Registry& registry, const std::vector<RunRequest>& requests, const RunOptions& options);

std::string default_shader_root();

}  // namespace oitbench
