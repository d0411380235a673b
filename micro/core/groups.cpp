#include "core/groups.hpp"

#include <algorithm>

namespace oitbench {

std::string baseline_text(const std::map<std::string, std::string>& baseline) {
  std::string s;
  for (const auto& [k, v] : baseline) s += (s.empty() ? "" : ";") + k + "=" + v;
  return s;
}

bool has_baseline_values(const ParamSet& p, const std::map<std::string, std::string>& baseline) {
  return std::all_of(baseline.begin(), baseline.end(),
                     [&](const auto& kv) { return p.has(kv.first) && p.get(kv.first) == kv.second; });
}

bool is_baseline_of(const ParamSet& base, const ParamSet& c, const std::map<std::string, std::string>& baseline) {
  if (baseline.empty() || !has_baseline_values(base, baseline) || has_baseline_values(c, baseline)) return false;
  for (const auto& [k, v] : c.used_values())
    if (!baseline.count(k) && base.uses(k) && base.get(k) != v) return false;
  return true;
}

std::vector<GroupPlan> plan_groups(const std::vector<ParamSet>& cases,
                                   const std::map<std::string, std::string>& baseline, size_t size) {
  size = std::max<size_t>(size, 1);
  std::vector<GroupPlan> groups;
  auto plain = [&](const std::vector<size_t>& idx) {
    for (size_t i = 0; i < idx.size(); i += size) {
      GroupPlan g;
      for (size_t j = i; j < std::min(idx.size(), i + size); ++j) {
        g.cases.push_back(cases[idx[j]]);
        g.baseline_of.push_back(-1);
        g.shadow.push_back(false);
      }
      groups.push_back(std::move(g));
    }
  };
  std::vector<size_t> all(cases.size());
  for (size_t i = 0; i < all.size(); ++i) all[i] = i;
  if (baseline.empty() || size < 2) {
    plain(all);
    return groups;
  }
  // Each case's baseline: the first case that is one for it.
  std::vector<int> base(cases.size(), -1);
  std::vector<std::vector<size_t>> dependents(cases.size());
  for (size_t i = 0; i < cases.size(); ++i)
    for (size_t b = 0; b < cases.size(); ++b)
      if (is_baseline_of(cases[b], cases[i], baseline)) {
        base[i] = static_cast<int>(b);
        dependents[b].push_back(i);
        break;
      }
  std::vector<size_t> rest;
  for (size_t i = 0; i < cases.size(); ++i) {
    if (base[i] >= 0) continue;  // runs with its baseline
    if (dependents[i].empty()) {
      rest.push_back(i);
      continue;
    }
    const auto& deps = dependents[i];
    for (size_t d = 0; d < deps.size(); d += size - 1) {
      GroupPlan g;
      g.cases.push_back(cases[i]);
      g.baseline_of.push_back(-1);
      g.shadow.push_back(d > 0);
      for (size_t j = d; j < std::min(deps.size(), d + size - 1); ++j) {
        g.cases.push_back(cases[deps[j]]);
        g.baseline_of.push_back(0);
        g.shadow.push_back(false);
      }
      groups.push_back(std::move(g));
    }
  }
  plain(rest);
  return groups;
}

}  // namespace oitbench
