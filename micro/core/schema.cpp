#include "core/schema.hpp"

#include <algorithm>
#include <map>
#include <nlohmann/json.hpp>

#include "core/registry.hpp"

namespace oitbench {

const char* status_name(Status s) {
  switch (s) {
    case Status::Ok:
      return "ok";
    case Status::Invalid:
      return "invalid";
    case Status::Unsupported:
      return "unsupported";
    case Status::Error:
      return "error";
    case Status::Timeout:
      return "timeout";
  }
  return "?";
}

const char* status_description(Status s) {
  switch (s) {
    case Status::Ok:
      return "ran and matched its reference: the times are valid";
    case Status::Invalid:
      return "ran but disagreed with its reference (reason says how): no times";
    case Status::Unsupported:
      return "this driver cannot run the case (reason says what is missing): no times";
    case Status::Error:
      return "failed to build or run (reason names the file and line or the GL error): no times";
    case Status::Timeout:
      return "killed by the watchdog after --timeout seconds: no times";
  }
  return "?";
}

const char* value_type_name(ValueType t) {
  switch (t) {
    case ValueType::Text:
      return "text";
    case ValueType::Integer:
      return "integer";
    case ValueType::Number:
      return "number";
    case ValueType::Flag:
      return "flag";
  }
  return "?";
}

namespace {
using T = ValueType;
}  // namespace

namespace {

// What a row is and where it ran: the case, its status, the context and driver.
std::vector<ColumnSpec> identity_columns() {
  return {
      {"schema", T::Integer, "", "version of this column layout (kCsvSchema)", "run"},
      {"experiment", T::Text, "", "experiment name (oitbench list)", "case"},
      {"variant", T::Text, "", "the experiment's variant parameter, where it has one", "case"},
      {"pass", T::Text, "", "the timed pass this row is about; total is the whole repetition", "case"},
      {"status", T::Text, "", "ok, invalid, unsupported, error or timeout (see statuses)", "result"},
      {"valid", T::Flag, "", "1 when status is ok, else 0", "result"},
      {"reason", T::Text, "", "why the case is not ok, or a note on an ok one", "result"},
      {"backend", T::Text, "", "context backend: egl, egl-device, osmesa, glfw", "run"},
      {"device", T::Text, "", "the display or EGL device the context ran on", "run"},
      {"device_drm_node", T::Text, "",
       "the DRM node of the EGL device the context ran on (EGL_DRM_DEVICE_FILE_EXT, else the render node); empty "
       "where unknown (the surfaceless platform, OSMesa, GLFW)",
       "run"},
      {"device_pci_bus", T::Text, "",
       "the PCI bus of that device (/sys/class/drm/NODE/device, e.g. 0000:01:00.0); empty where unknown", "run"},
      {"driver", T::Text, "",
       "the GL driver, named from its GL strings: llvmpipe, zink-lavapipe, nvidia-h200, ... "
       "(--driver selects one; see oitbench info --drivers)",
       "run"},
      {"gl_vendor", T::Text, "", "GL_VENDOR", "run"},
      {"gl_renderer", T::Text, "", "GL_RENDERER", "run"},
      {"gl_version", T::Text, "", "GL_VERSION", "run"},
      {"gpu_driver_version", T::Text, "",
       "the GPU driver's version as NVML reports it (nvmlSystemGetDriverVersion), where GL_VENDOR is NVIDIA's and "
       "libnvidia-ml.so.1 loads; empty elsewhere",
       "run"},
      {"gpu_pci_id", T::Text, "",
       "the GPU's PCI vendor:device ID (10de:2335) from NVML, else from sysfs for device_pci_bus; empty where unknown "
       "(llvmpipe)",
       "run"},
      {"gpu_vbios_version", T::Text, "",
       "the GPU's VBIOS version from NVML (nvmlDeviceGetVbiosVersion), else sysfs's vbios_version for device_pci_bus "
       "(amdgpu); empty where unknown",
       "run"},
  };
}

// How the case was timed: size, repetitions, statistics, speedups, the clocks' and GPU state.
std::vector<ColumnSpec> timing_columns() {
  return {
      {"width", T::Integer, "px", "render target width", "case"},
      {"height", T::Integer, "px", "render target height", "case"},
      {"reps", T::Integer, "",
       "timed repetitions the case got: the fixed count (--reps, a preset's reps), or where the stopping rule "
       "stopped (see stop)",
       "case"},
      {"warmup", T::Integer, "",
       "untimed repetitions before them: --warmup (a preset's warmup), one fewer where the last had settled and "
       "counted as the first timed repetition",
       "case"},
      {"median_ms", T::Number, "ms", "median of the primary clock over the repetitions", "timing"},
      {"mad_ms", T::Number, "ms", "median absolute deviation of the primary clock", "timing"},
      {"min_ms", T::Number, "ms", "fastest repetition", "timing"},
      {"max_ms", T::Number, "ms", "slowest repetition", "timing"},
      {"mean_ms", T::Number, "ms", "mean of the repetitions", "timing"},
      {"stddev_ms", T::Number, "ms", "standard deviation of the repetitions", "timing"},
      {"samples", T::Integer, "", "repetitions the statistics are over", "timing"},
      {"outliers", T::Integer, "", "repetitions more than 5 MADs (5% where the MAD is 0) from the median", "timing"},
      {"ci_lo_ms", T::Number, "ms",
       "lower end of the 95% distribution-free interval of median_ms (order statistics); empty below 6 samples",
       "timing"},
      {"ci_hi_ms", T::Number, "ms", "upper end of that interval", "timing"},
      {"ci_pct", T::Number, "%", "the interval's larger distance from median_ms, in % of it (3: within +-3%)",
       "timing"},
      {"target_ci_pct", T::Number, "%",
       "--target-ci the stopping rule aimed at (the total's interval); empty for a fixed count", "timing"},
      {"stop", T::Text, "",
       "why the repetitions stopped: fixed (--reps or a preset's reps), target (its interval reached "
       "target_ci_pct; a baseline's once its cases' had too), max-reps or max-case-s (a limit; reason says when the "
       "target was missed)",
       "timing"},
      {"sample_runs", T::Integer, "",
       "runs of the case's repetition inside one sample (chosen from the warm-up so a sample lasts "
       "--min-sample-ms); times are per repetition",
       "timing"},
      {"sample_units", T::Integer, "",
       "units of work (occupancy: draws) one run did, where the experiment scales them (a repetition longer than "
       "--max-sample-ms runs fewer); times are scaled to the nominal repetition. Empty: not scalable",
       "timing"},
      {"baseline", T::Text, "",
       "the case the speedup divides by, NAME=VALUE;... (a preset's or --baseline's), run in the same interleaved "
       "group",
       "timing"},
      {"speedup", T::Number, "x",
       "median over repetitions of baseline time / this case's time, each pair from one round of the same group "
       "(primary clock, same pass)",
       "timing"},
      {"speedup_ci_lo", T::Number, "x", "lower end of the speedup's 95% interval (order statistics of the ratios)",
       "timing"},
      {"speedup_ci_hi", T::Number, "x", "upper end of the speedup's 95% interval", "timing"},
      {"cpu_median_ms", T::Number, "ms", "median of the CPU clock around glFinish", "timing"},
      {"cpu_mad_ms", T::Number, "ms", "its median absolute deviation", "timing"},
      {"gpu_median_ms", T::Number, "ms", "median of the GL_TIME_ELAPSED queries, where the driver has them", "timing"},
      {"gpu_mad_ms", T::Number, "ms", "its median absolute deviation", "timing"},
      {"timer", T::Text, "", "the primary clock of median_ms: cpu or gpu (total and CPU passes: always cpu)", "timing"},
      {"pass_sync", T::Flag, "",
       "1: every pass bracketed by glFinish, so cpu_median_ms is its work (software "
       "renderers, --sync-passes); 0: passes ran back to back, timed by their queries, "
       "and a pass's cpu_median_ms is its submission",
       "timing"},
      {"compile_ms", T::Number, "ms",
       "preparing the case: compile, link, allocate, upload (a scene's meshes: once per run, by the first case that "
       "draws them)",
       "timing"},
      {"program_cache", T::Text, "", "hit, miss, partial or off: whether compile_ms paid for compiling", "timing"},
      {"warmup_ms", T::Number, "ms",
       "the first (untimed) repetition, JIT included; where the work scales (sample_units), one unit of it", "timing"},
      {"host_mem_ns", T::Number, "ns",
       "the host's memory latency while the case ran: median over its timed rounds of a dependent-load chase "
       "through 64 MiB (--mem-probe-mib) after each round (core/memory_probe.hpp); empty with --no-mem-probe. On a "
       "software renderer this is the GPU's memory: a resolve that walks lists follows it, a sort in local arrays does "
       "not",
       "timing"},
      {"host_mem_max_ns", T::Number, "ns",
       "the slowest of those chases: a memory-latency episode during the case (another tenant's traffic on a "
       "shared host) shows here, beside times it slowed (docs/drivers.md)",
       "timing"},
  };
}

// Where the case's wall time went (the time account): its phases outside and inside the samples.
std::vector<ColumnSpec> phase_columns() {
  return {
      {"case_wall_s", T::Number, "s",
       "the case's wall time, the sum of its phase_*_s columns (total row only): from its prepare to its validation's "
       "end, the runner's own work in its interleaved group shared equally among the group's cases; the run's start "
       "and the writing of rows are the run's (the summary line on stderr)",
       "timing"},
      {"phase_scene_s", T::Number, "s",
       "of case_wall_s: preparing the case apart from compiling and pool sizing (scene build and upload, buffers, "
       "render targets; a scene shared by the run is paid by the first case that draws it)",
       "timing"},
      {"phase_compile_s", T::Number, "s",
       "of case_wall_s: compiling and linking programs (program-cache loads included), wherever the case did it",
       "timing"},
      {"phase_pool_s", T::Number, "s",
       "of case_wall_s: sizing the case's storage (the exact techniques' count pass that sizes a fragment pool and "
       "its read-back of the counts; with initial_pool, the capture, its overflow re-renders and read-back)",
       "timing"},
      {"phase_warmup_s", T::Number, "s",
       "of case_wall_s: untimed repetitions (not a last one that settled and counted as a sample), and rounds the "
       "sample-size check took as warm-up",
       "timing"},
      {"phase_samples_s", T::Number, "s", "of case_wall_s: the timed repetitions", "timing"},
      {"phase_readback_s", T::Number, "s", "of case_wall_s: reading the result back for validation", "timing"},
      {"phase_reference_s", T::Number, "s", "of case_wall_s: computing the CPU or geometric reference", "timing"},
      {"phase_validate_s", T::Number, "s",
       "of case_wall_s: validation apart from read-back and reference (comparison, metrics)", "timing"},
      {"phase_other_s", T::Number, "s",
       "of case_wall_s: the measured remainder (the runner's work between phases: progress, GPU state, the "
       "stopping rule, raw rows)",
       "timing"},
  };
}

// The GPU's state around the case group (NVML), to tell throttling from a slower case.
std::vector<ColumnSpec> gpu_state_columns() {
  return {
      {"gpu_sm_clock_start_mhz", T::Integer, "MHz",
       "the GPU's SM clock (NVML) just before the case group's first warm-up repetition; empty without NVML", "timing"},
      {"gpu_sm_clock_end_mhz", T::Integer, "MHz",
       "the SM clock just after the group's last timed repetition (a change over 5% is noted in reason)", "timing"},
      {"gpu_mem_clock_start_mhz", T::Integer, "MHz", "the memory clock (NVML) at the start of the case group",
       "timing"},
      {"gpu_mem_clock_end_mhz", T::Integer, "MHz", "the memory clock at the end of the case group", "timing"},
      {"gpu_temp_start_c", T::Integer, "C", "the GPU temperature (NVML) at the start of the case group", "timing"},
      {"gpu_temp_end_c", T::Integer, "C", "the GPU temperature at the end of the case group", "timing"},
      {"gpu_power_start_w", T::Number, "W", "the board power draw (NVML) at the start of the case group", "timing"},
      {"gpu_power_end_w", T::Number, "W", "the board power draw at the end of the case group", "timing"},
  };
}

// Which run and machine wrote the row: preset, shard, commit, host, run identity, CPU, Mesa/LLVM.
std::vector<ColumnSpec> provenance_columns() {
  return {
      {"preset", T::Text, "", "the preset the row ran under, if any", "run"},
      {"shard", T::Text, "",
       "I/N: the row ran in shard I of N (--shard; the N shards' rows together are the whole grid, each case "
       "once); empty: the whole grid in one run",
       "run"},
      {"git_sha", T::Text, "", "the commit the binary was built from (-dirty when its sources differed)", "run"},
      {"timestamp_utc", T::Text, "", "when the row was written (ISO 8601, UTC)", "run"},
      {"hostname", T::Text, "", "machine name", "run"},
      {"cpu_model", T::Text, "", "/proc/cpuinfo model name", "run"},
      {"lp_num_threads", T::Text, "", "LP_NUM_THREADS (llvmpipe's rasterizer threads), or the core count", "run"},
      {"env", T::Text, "", "environment variables that change a driver's behaviour, NAME=VALUE;...", "run"},
      {"run_id", T::Text, "",
       "the invocation's UUID (version 4): every row and raw sample one oitbench run writes carries the same one",
       "run"},
      {"tags", T::Text, "",
       "the --tag KEY=VALUE labels, KEY=VALUE;... sorted by key; '%', ';' and '=' in values as %25, %3B, %3D", "run"},
      {"cpu_vendor", T::Text, "", "/proc/cpuinfo vendor_id (GenuineIntel, AuthenticAMD; arm: CPU implementer)", "run"},
      {"cpu_family", T::Text, "", "/proc/cpuinfo cpu family", "run"},
      {"cpu_model_id", T::Text, "", "/proc/cpuinfo model (the number; cpu_model is the name)", "run"},
      {"cpu_stepping", T::Text, "", "/proc/cpuinfo stepping", "run"},
      {"cpu_isa", T::Text, "",
       "the ISA extensions a JIT such as llvmpipe's LLVM may use that the CPU has (sse4_2 avx avx2 fma avx512f ...), "
       "space-separated in a fixed order",
       "run"},
      {"cpu_count", T::Integer, "", "logical CPUs in /proc/cpuinfo", "run"},
      {"memory_bytes", T::Integer, "bytes", "MemTotal of /proc/meminfo", "run"},
      {"kernel", T::Text, "", "uname release and version", "run"},
      {"machine_id", T::Text, "",
       "16 hex digits: a hash of the CPU's vendor, family, model, stepping, name, ISA extensions and count, the memory "
       "and the kernel; two machines under one hostname and cpu_model differ here",
       "run"},
      {"mesa_version", T::Text, "", "Mesa NN.N.N from GL_VERSION, where the driver is Mesa's", "run"},
      {"llvm_version", T::Text, "", "the LLVM llvmpipe JITs with, from GL_RENDERER (llvmpipe, zink over lavapipe)",
       "run"},
      {"llvm_vector_bits", T::Integer, "bits",
       "the vector width llvmpipe targets, from GL_RENDERER (256: AVX2; LP_NATIVE_VECTOR_WIDTH changes it)", "run"},
      {"parameters", T::Text, "", "the parameter columns this case uses, NAME;NAME;...", "case"},
  };
}

}  // namespace

const std::vector<ColumnSpec>& summary_base_columns() {
  static const std::vector<ColumnSpec> cols = [] {
    std::vector<ColumnSpec> c = identity_columns();
    for (auto part : {timing_columns(), phase_columns(), gpu_state_columns(), provenance_columns()})
      c.insert(c.end(), part.begin(), part.end());
    return c;
  }();
  return cols;
}

const std::vector<ColumnSpec>& raw_base_columns() {
  static const std::vector<ColumnSpec> cols = {
      {"schema", T::Integer, "", "version of this column layout", "run"},
      {"experiment", T::Text, "", "experiment name", "case"},
      {"variant", T::Text, "", "the experiment's variant parameter", "case"},
      {"pass", T::Text, "", "the timed pass; total is the whole repetition", "case"},
      {"rep", T::Integer, "", "repetition index, 0 = first timed one", "case"},
      {"width", T::Integer, "px", "render target width (as in the summary file)", "case"},
      {"height", T::Integer, "px", "render target height", "case"},
      {"cpu_ms", T::Number, "ms", "CPU clock around glFinish", "timing"},
      {"gpu_ms", T::Number, "ms", "GL_TIME_ELAPSED, where the driver has it", "timing"},
      {"sample_runs", T::Integer, "", "runs of the repetition in this sample (cpu_ms, gpu_ms are per repetition)",
       "timing"},
      {"sample_units", T::Integer, "", "units of work per run where the experiment scales them (see the summary)",
       "timing"},
      {"group", T::Integer, "",
       "the interleaved group the sample ran in (per run, from 0): samples of one group and rep ran in one round, so "
       "they pair",
       "case"},
      {"backend", T::Text, "", "context backend", "run"},
      {"driver", T::Text, "", "the GL driver (as in the summary file)", "run"},
      {"gl_renderer", T::Text, "", "GL_RENDERER", "run"},
      {"git_sha", T::Text, "", "the commit the binary was built from", "run"},
      {"timestamp_utc", T::Text, "", "when the row was written", "run"},
      {"preset", T::Text, "", "the preset the row ran under", "run"},
      {"shard", T::Text, "", "I/N: the shard the row ran in (--shard); empty: unsharded", "run"},
      {"run_id", T::Text, "", "the invocation's UUID, as in the summary file", "run"},
  };
  return cols;
}

namespace {

void append_unique(std::vector<std::string>& v, const std::string& s) {
  if (std::find(v.begin(), v.end(), s) == v.end()) v.push_back(s);
}

std::vector<std::string> names_of(const std::vector<ColumnSpec>& cols) {
  std::vector<std::string> v;
  for (const auto& c : cols) v.push_back(c.name);
  return v;
}

std::vector<std::string> parameter_names(const Registry& registry) {
  std::vector<std::string> v;
  for (const auto& e : registry.all())
    for (const auto& p : registry.params_of(*e))
      if (p.name != "variant") append_unique(v, p.name);
  return v;
}

const char* param_type(ParamSpec::Kind k) {
  return k == ParamSpec::Kind::Integer ? "integer" : k == ParamSpec::Kind::Number ? "number" : "text";
}

}  // namespace

std::vector<std::string> summary_columns(const Registry& registry) {
  auto cols = names_of(summary_base_columns());
  for (const auto& e : registry.all())
    for (const auto& m : e->metric_specs()) append_unique(cols, m.name);
  for (const auto& p : parameter_names(registry)) append_unique(cols, p);
  return cols;
}

std::vector<std::string> raw_columns(const Registry& registry) {
  auto cols = names_of(raw_base_columns());
  for (const auto& p : parameter_names(registry)) append_unique(cols, p);
  return cols;
}

std::string schema_json(const Registry& registry) {
  using nlohmann::ordered_json;
  auto column = [](const ColumnSpec& c, const char* role) {
    ordered_json j;
    j["name"] = c.name;
    j["role"] = role;
    j["type"] = value_type_name(c.type);
    j["unit"] = c.unit;
    j["description"] = c.description;
    if (!c.group.empty()) j["group"] = c.group;
    return j;
  };
  // Metrics and parameters: one entry per name, with the experiments that fill it.
  std::vector<std::string> order;
  std::map<std::string, ordered_json> entries;
  for (const auto& e : registry.all())
    for (const auto& m : e->metric_specs()) {
      if (!entries.count(m.name)) {
        entries[m.name] = column(m, "metric");
        entries[m.name]["experiments"] = ordered_json::array();
        order.push_back(m.name);
      }
      entries[m.name]["experiments"].push_back(e->name());
    }
  std::vector<std::string> params;
  std::map<std::string, ordered_json> param_entries;
  for (const auto& e : registry.all())
    for (const auto& p : registry.params_of(*e)) {
      if (p.name == "variant") continue;
      if (!param_entries.count(p.name)) {
        ordered_json j;
        j["name"] = p.name;
        j["role"] = "parameter";
        j["type"] = param_type(p.kind);
        j["unit"] = "";
        j["description"] = p.description;
        j["experiments"] = ordered_json::array();
        param_entries[p.name] = j;
        params.push_back(p.name);
      }
      param_entries[p.name]["experiments"].push_back(e->name());
      if (!p.applies_when.empty()) param_entries[p.name]["applies_where"][e->name()] = p.scope_text();
    }
  ordered_json out;
  out["schema"] = kCsvSchema;
  out["statuses"] = ordered_json::array();
  for (Status s : kAllStatuses)
    out["statuses"].push_back({{"name", status_name(s)}, {"meaning", status_description(s)}});
  auto& summary = out["summary_columns"] = ordered_json::array();
  for (const auto& c : summary_base_columns()) summary.push_back(column(c, "base"));
  for (const auto& n : order) summary.push_back(entries[n]);
  for (const auto& n : params)
    if (!entries.count(n)) summary.push_back(param_entries[n]);
  auto& raw = out["raw_columns"] = ordered_json::array();
  for (const auto& c : raw_base_columns()) raw.push_back(column(c, "base"));
  for (const auto& n : params) raw.push_back(param_entries[n]);
  return out.dump(2) + "\n";
}

}  // namespace oitbench
