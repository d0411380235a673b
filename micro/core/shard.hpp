#pragma once
// Shards: `oitbench run ... --shard I/N` runs the I-th of N deterministic parts of the grid, so N workers
// of a fleet (a Slurm array, a Kubernetes Indexed Job, GitLab's parallel:) run every case exactly once
// between them. The parts are made of whole units (core/plan.hpp: an interleaved group with the baseline
// its speedups pair with, or one isolated case), never of pieces of one.
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace oitbench {

struct ShardSpec {
  int index = 0;       // 1-based: 1..count
  int count = 0;       // 0: no sharding (the whole grid)
  std::string source;  // where auto found it: "SLURM_ARRAY_TASK_ID=3 ..."; empty for I/N
  bool active() const { return count > 0; }
  std::string text() const;  // "2/4"; empty without sharding
};

inline constexpr int kMaxShards = 100000;

// The environment as a function (tests pass a map): the value of a variable, or nullptr when unset.
using EnvLookup = std::function<const char*(const char*)>;
EnvLookup process_env();

// Parses --shard: "I/N" (1 <= I <= N) or "auto" (the scheduler's variables, see docs/ci.md):
//   Slurm arrays       SLURM_ARRAY_TASK_ID, SLURM_ARRAY_TASK_MIN, SLURM_ARRAY_TASK_COUNT (and _MAX, _STEP)
//   Kubernetes         JOB_COMPLETION_INDEX (0-based) with OITBENCH_SHARD_COUNT (the Job's completions)
//   GitLab parallel:   CI_NODE_INDEX (1-based), CI_NODE_TOTAL
// Throws UsageError naming --shard and what is valid.
ShardSpec parse_shard(const std::string& text, const EnvLookup& env = process_env());

// The shard (0-based) of each unit: the units in order, each to the shard with the fewest cases so far
// (the lowest-numbered on a tie). `cases_of_unit[k]` is the number of rows unit k writes.
std::vector<int> assign_shards(const std::vector<size_t>& cases_of_unit, int count);

}  // namespace oitbench
