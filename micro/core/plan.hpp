#pragma once
// The run's plan, made before any GL work and without a context: the requests expanded into their
// grids (Planned), the grids cut into units of work (an interleaved group, or one case run in a child
// process) and, with --shard, the units this shard runs. A test walks it for every preset.
#include <string>
#include <vector>

#include "core/groups.hpp"
#include "core/runner.hpp"
#include "core/shard.hpp"

namespace oitbench {

// One request's sizes and grid.
struct Planned {
  Experiment* exp;
  Resolution res;
  int reps, warmup;
  std::vector<ParamSet> cases;
  SamplingPolicy policy;                        // fixed `reps`, or the stopping rule
  std::map<std::string, std::string> baseline;  // the request's baseline (speedups), empty: none
};

// `hardware_driver`: the sizes and grids of a hardware driver (a preset entry's "hardware"), else a
// software renderer's.
std::vector<Planned> make_plan(Registry& registry, const std::vector<RunRequest>& requests, const RunOptions& options,
                               bool hardware_driver);

// A unit of work: one interleaved group (its cases, each baseline with the cases it pairs with), or one
// case in a child process (`isolated`; the group then holds that case alone). Units are never split.
struct RunUnit {
  size_t planned = 0;  // index in the plan
  bool isolated = false;
  GroupPlan group;
  size_t rows() const;  // the cases it writes rows for (a baseline's shadow copies write none)
};

// The plan's units in run order. With `shard` active, only that shard's (core/shard.hpp).
std::vector<RunUnit> plan_units(const std::vector<Planned>& plan, const RunOptions& options,
                                const ShardSpec& shard = {});

// The stable key of a case, what --expect patterns and JUnit names match:
// "EXPERIMENT/WIDTHxHEIGHT/name=value/..." over the parameters the case uses, in the experiment's order,
// but `fault`: an injected fault is a broken run of the same case, which a baseline must catch.
std::string case_key(const std::string& experiment, Resolution res, const ParamSet& params);

}  // namespace oitbench
