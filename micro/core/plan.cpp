#include "core/plan.hpp"

#include <algorithm>

namespace oitbench {

std::vector<Planned> make_plan(Registry& registry, const std::vector<RunRequest>& requests, const RunOptions& options,
                               bool hardware_driver) {
  std::vector<Planned> plan;
  for (const auto& r : requests) {
    Experiment* e = registry.find(r.experiment);
    const bool quick = options.quick || r.quick;
    RunSize size = resolve_run_size(r, *e, options, hardware_driver);
    SamplingPolicy policy = options.sampling;
    policy.adaptive = !size.fixed_reps;
    policy.reps = size.reps;
    plan.push_back(
        {e, size.resolution, size.reps, size.warmup,
         expand_grid(registry.params_of(*e), request_overrides(r, hardware_driver), quick, options.max_cases), policy,
         r.baseline});
  }
  return plan;
}

size_t RunUnit::rows() const {
  return static_cast<size_t>(std::count(group.shadow.begin(), group.shadow.end(), false));
}

std::vector<RunUnit> plan_units(const std::vector<Planned>& plan, const RunOptions& options, const ShardSpec& shard) {
  std::vector<RunUnit> units;
  for (size_t i = 0; i < plan.size(); ++i) {
    const Planned& p = plan[i];
    const bool isolate = options.isolate == "always" || (options.isolate == "auto" && p.exp->hang_prone());
    if (isolate) {
      for (const auto& c : p.cases) units.push_back({i, true, GroupPlan{{c}, {-1}, {false}}});
      continue;
    }
    const size_t chunk = options.interleave ? static_cast<size_t>(std::max(1, p.exp->max_interleave(p.res))) : 1;
    for (auto& g : plan_groups(p.cases, p.baseline, chunk)) units.push_back({i, false, std::move(g)});
  }
  if (!shard.active()) return units;
  std::vector<size_t> sizes;
  for (const auto& u : units) sizes.push_back(u.rows());
  const auto owner = assign_shards(sizes, shard.count);
  std::vector<RunUnit> mine;
  for (size_t k = 0; k < units.size(); ++k)
    if (owner[k] == shard.index - 1) mine.push_back(std::move(units[k]));
  return mine;
}

std::string case_key(const std::string& experiment, Resolution res, const ParamSet& params) {
  std::string key = experiment + "/" + std::to_string(res.width) + "x" + std::to_string(res.height);
  for (const auto& [k, v] : params.used_values())
    if (k != "fault") key += "/" + k + "=" + v;
  return key;
}

}  // namespace oitbench
