#pragma once
// The run's plan, made before any GL work and without a context: the requests with their grids
// (Planned; a grid is numbered, never held: core/grid.hpp), the grids cut into units of work (an
// interleaved group, or one case run in a child process) made one at a time as the run reaches them
// and, with --shard, the units this shard runs. A test walks it for every preset.
#include <memory>
#include <queue>
#include <string>
#include <vector>

#include "core/grid.hpp"
#include "core/groups.hpp"
#include "core/runner.hpp"
#include "core/shard.hpp"

namespace oitbench {

// One request's sizes and grid.
struct Planned {
  Experiment* exp;
  Resolution res;
  int reps, warmup;
  std::shared_ptr<const CaseGrid> grid;         // the request's cases, built as they run
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

// The plan's units in run order, made one at a time: a unit's cases are built when next() reaches it, so
// the memory holds one unit whatever the size of the grid. With `shard` active, only that shard's units
// (core/shard.hpp: each unit to the shard with the fewest cases so far); the others are walked without
// building their cases. A request with a baseline pairs its cases across the whole grid: its cases are
// held while its units are made (plan_groups), the one place memory grows with a grid.
class UnitStream {
 public:
  UnitStream(const std::vector<Planned>& plan, const RunOptions& options, const ShardSpec& shard = {});
  bool next(RunUnit& unit);  // false after the last
  size_t count_rows();       // the rows the units not yet made write (walks them without building; ends the stream)

 private:
  struct Pending {  // a unit before its cases are built: their numbers in the grid, or a paired group
    size_t planned = 0;
    bool isolated = false;
    std::vector<uint64_t> numbers;
    size_t paired = 0;  // index in paired_ when `numbers` is empty
    size_t rows = 0;
  };
  bool next_pending(Pending& u);
  bool mine(size_t rows);  // the shard that takes a unit of `rows` rows is this one

  const std::vector<Planned>& plan_;
  const RunOptions& options_;
  ShardSpec shard_;
  size_t planned_ = 0;
  uint64_t at_ = 0;       // the next number of plan_[planned_]'s grid
  bool started_ = false;  // plan_[planned_]'s mode is set
  bool isolate_ = false, pairing_ = false;
  size_t chunk_ = 1;
  std::vector<GroupPlan> paired_;       // a request with a baseline: its groups
  using Load = std::pair<size_t, int>;  // a shard's rows so far, its index
  std::priority_queue<Load, std::vector<Load>, std::greater<>> loads_;
};

// Every unit of the stream, in memory: tests and small plans.
std::vector<RunUnit> plan_units(const std::vector<Planned>& plan, const RunOptions& options,
                                const ShardSpec& shard = {});

// The stable key of a case, what --expect patterns and JUnit names match:
// "EXPERIMENT/WIDTHxHEIGHT/name=value/..." over the parameters the case uses, in the experiment's order,
// but `fault`: an injected fault is a broken run of the same case, which a baseline must catch.
std::string case_key(const std::string& experiment, Resolution res, const ParamSet& params);

}  // namespace oitbench
