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
    auto grid = std::make_shared<const CaseGrid>(registry.params_of(*e), request_overrides(r, hardware_driver), quick,
                                                 options.max_cases);
    plan.push_back({e, size.resolution, size.reps, size.warmup, std::move(grid), policy, r.baseline});
  }
  return plan;
}

size_t RunUnit::rows() const {
  return static_cast<size_t>(std::count(group.shadow.begin(), group.shadow.end(), false));
}

UnitStream::UnitStream(const std::vector<Planned>& plan, const RunOptions& options, const ShardSpec& shard)
    : plan_(plan), options_(options), shard_(shard) {
  if (shard_.active())
    for (int i = 0; i < shard_.count; ++i) loads_.push({0, i});
}

// assign_shards, one unit at a time: the unit goes to the shard with the fewest rows so far (the
// lowest-numbered on a tie).
bool UnitStream::mine(size_t rows) {
  if (!shard_.active()) return true;
  Load least = loads_.top();
  loads_.pop();
  const bool own = least.second == shard_.index - 1;
  least.first += rows;
  loads_.push(least);
  return own;
}

bool UnitStream::next_pending(Pending& u) {
  for (; planned_ < plan_.size(); ++planned_, started_ = false) {
    const Planned& p = plan_[planned_];
    if (!started_) {  // the request's units: one isolated case each, groups paired with a baseline, or chunks
      isolate_ = options_.isolate == "always" || (options_.isolate == "auto" && p.exp->hang_prone());
      chunk_ = isolate_ || !options_.interleave ? 1 : static_cast<size_t>(std::max(1, p.exp->max_interleave(p.res)));
      pairing_ = !isolate_ && !p.baseline.empty() && chunk_ >= 2;
      paired_ = pairing_ ? plan_groups(p.grid->cases(), p.baseline, chunk_) : std::vector<GroupPlan>{};
      at_ = 0;
      started_ = true;
    }
    u = Pending{};
    u.planned = planned_;
    u.isolated = isolate_;
    if (pairing_) {
      if (at_ >= paired_.size()) continue;
      u.paired = static_cast<size_t>(at_++);
      u.rows = static_cast<size_t>(std::count(paired_[u.paired].shadow.begin(), paired_[u.paired].shadow.end(), false));
      return true;
    }
    for (uint64_t n = p.grid->next_case(at_); n < p.grid->raw_size() && u.numbers.size() < chunk_;
         n = p.grid->next_case(n + 1)) {
      u.numbers.push_back(n);
      at_ = n + 1;
    }
    if (u.numbers.empty()) continue;
    u.rows = u.numbers.size();
    return true;
  }
  return false;
}

bool UnitStream::next(RunUnit& unit) {
  Pending u;
  while (next_pending(u)) {
    if (!mine(u.rows)) continue;
    unit = RunUnit{u.planned, u.isolated, GroupPlan{}};
    if (pairing_) {
      unit.group = std::move(paired_[u.paired]);
      return true;
    }
    for (const uint64_t n : u.numbers) {
      unit.group.cases.push_back(plan_[u.planned].grid->case_at(n));
      unit.group.baseline_of.push_back(-1);
      unit.group.shadow.push_back(false);
    }
    return true;
  }
  return false;
}

size_t UnitStream::count_rows() {
  size_t rows = 0;
  for (Pending u; next_pending(u);)
    if (mine(u.rows)) rows += u.rows;
  return rows;
}

std::vector<RunUnit> plan_units(const std::vector<Planned>& plan, const RunOptions& options, const ShardSpec& shard) {
  std::vector<RunUnit> units;
  UnitStream stream(plan, options, shard);
  for (RunUnit u; stream.next(u);) units.push_back(std::move(u));
  return units;
}

std::string case_key(const std::string& experiment, Resolution res, const ParamSet& params) {
  std::string key = experiment + "/" + std::to_string(res.width) + "x" + std::to_string(res.height);
  for (const auto& [k, v] : params.used_values())
    if (k != "fault") key += "/" + k + "=" + v;
  return key;
}

}  // namespace oitbench
