#include "core/shard.hpp"

#include <algorithm>
#include <cstdlib>

#include "core/params.hpp"

namespace oitbench {

std::string ShardSpec::text() const {
  return active() ? std::to_string(index) + "/" + std::to_string(count) : std::string();
}

EnvLookup process_env() {
  return [](const char* name) -> const char* { return std::getenv(name); };
}

namespace {

constexpr const char* kValid =
    "give I/N with 1 <= I <= N (e.g. --shard 2/4), or auto inside a Slurm array job (SLURM_ARRAY_TASK_ID), a "
    "Kubernetes Indexed Job (JOB_COMPLETION_INDEX with OITBENCH_SHARD_COUNT) or a GitLab parallel: job "
    "(CI_NODE_INDEX, CI_NODE_TOTAL)";

// A whole decimal number in [lo, hi], else nullopt-like -1 (every bound here is >= 0).
long parse_count(const std::string& s, long lo, long hi) {
  if (s.empty() || s.size() > 9 || !std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; }))
    return -1;
  long v = std::stol(s);
  return v < lo || v > hi ? -1 : v;
}

long env_number(const EnvLookup& env, const char* name, const std::string& why) {
  const char* v = env(name);
  if (!v) throw UsageError("--shard auto: " + why + ", but " + name + " is not set; " + kValid);
  long n = parse_count(v, 0, kMaxShards * 10L);
  if (n < 0) throw UsageError("--shard auto: " + std::string(name) + "='" + v + "' is not a whole number");
  return n;
}

ShardSpec checked(long index, long count, const std::string& source) {
  if (count < 1 || count > kMaxShards || index < 1 || index > count)
    throw UsageError("--shard auto: " + source + " gives shard " + std::to_string(index) + " of " +
                     std::to_string(count) + ", which is not 1..N with N <= " + std::to_string(kMaxShards));
  return {static_cast<int>(index), static_cast<int>(count), source};
}

ShardSpec from_slurm(const EnvLookup& env) {
  const std::string why = "SLURM_ARRAY_TASK_ID is set";
  const long id = env_number(env, "SLURM_ARRAY_TASK_ID", why);
  const long min = env_number(env, "SLURM_ARRAY_TASK_MIN", why);
  const long count = env_number(env, "SLURM_ARRAY_TASK_COUNT", why);
  const long step = env("SLURM_ARRAY_TASK_STEP") ? env_number(env, "SLURM_ARRAY_TASK_STEP", why) : 1;
  const long max =
      env("SLURM_ARRAY_TASK_MAX") ? env_number(env, "SLURM_ARRAY_TASK_MAX", why) : min + (count - 1) * step;
  // An array like --array=1,3,10 has no arithmetic from its IDs to 1..N.
  if (step < 1 || (max - min) % step != 0 || (max - min) / step + 1 != count || id < min || (id - min) % step != 0)
    throw UsageError("--shard auto: the Slurm array (SLURM_ARRAY_TASK_MIN=" + std::to_string(min) +
                     ", _MAX=" + std::to_string(max) + ", _STEP=" + std::to_string(step) +
                     ", _COUNT=" + std::to_string(count) + ") is not a range A-B[:S]; submit one (e.g. --array=0-3)");
  const std::string source = "Slurm array: SLURM_ARRAY_TASK_ID=" + std::to_string(id) +
                             " of SLURM_ARRAY_TASK_MIN..MAX=" + std::to_string(min) + ".." + std::to_string(max);
  return checked((id - min) / step + 1, count, source);
}

ShardSpec from_kubernetes(const EnvLookup& env) {
  const long index = env_number(env, "JOB_COMPLETION_INDEX", "JOB_COMPLETION_INDEX is set");
  // A pod does not see its Job's completions: the manifest passes the same number (deploy/kubernetes/).
  const long count = env_number(env, "OITBENCH_SHARD_COUNT",
                                "JOB_COMPLETION_INDEX is set (a Kubernetes Indexed Job) and the number of shards "
                                "must be the Job's completions");
  return checked(index + 1, count,
                 "Kubernetes Indexed Job: JOB_COMPLETION_INDEX=" + std::to_string(index) +
                     ", OITBENCH_SHARD_COUNT=" + std::to_string(count));
}

ShardSpec from_gitlab(const EnvLookup& env) {
  const long index = env_number(env, "CI_NODE_INDEX", "CI_NODE_INDEX is set");
  const long total = env_number(env, "CI_NODE_TOTAL", "CI_NODE_INDEX is set (GitLab parallel:)");
  return checked(
      index, total,
      "GitLab parallel: CI_NODE_INDEX=" + std::to_string(index) + ", CI_NODE_TOTAL=" + std::to_string(total));
}

}  // namespace

ShardSpec parse_shard(const std::string& text, const EnvLookup& env) {
  if (text == "auto") {
    if (env("SLURM_ARRAY_TASK_ID")) return from_slurm(env);
    if (env("JOB_COMPLETION_INDEX")) return from_kubernetes(env);
    if (env("CI_NODE_INDEX")) return from_gitlab(env);
    throw UsageError(std::string("--shard auto: no scheduler's variables are set; ") + kValid);
  }
  const auto slash = text.find('/');
  const long index = slash == std::string::npos ? -1 : parse_count(text.substr(0, slash), 1, kMaxShards);
  const long count = slash == std::string::npos ? -1 : parse_count(text.substr(slash + 1), 1, kMaxShards);
  if (index < 1 || count < 1 || index > count)
    throw UsageError("--shard '" + text + "': " + kValid + "; N at most " + std::to_string(kMaxShards));
  return {static_cast<int>(index), static_cast<int>(count), ""};
}

std::vector<int> assign_shards(const std::vector<size_t>& cases_of_unit, int count) {
  std::vector<int> shard(cases_of_unit.size(), 0);
  if (count < 1) return shard;
  std::vector<size_t> load(static_cast<size_t>(count), 0);
  for (size_t k = 0; k < cases_of_unit.size(); ++k) {
    const auto least = std::min_element(load.begin(), load.end());  // the first of equal loads
    shard[k] = static_cast<int>(least - load.begin());
    *least += cases_of_unit[k];
  }
  return shard;
}

}  // namespace oitbench
