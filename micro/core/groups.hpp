#pragma once
// Interleaved groups: which cases run their repetitions together (A B C A B C ...). Where a request names
// a baseline (a preset's "baseline", --baseline NAME=VALUE), every group that holds a case also holds the
// baseline it is divided by, so a speedup pairs samples of the same rounds and never spans two groups.
#include <map>
#include <string>
#include <vector>

#include "core/params.hpp"

namespace oitbench {

struct GroupPlan {
  std::vector<ParamSet> cases;
  std::vector<int> baseline_of;  // index in `cases` of the case's baseline; -1: none
  std::vector<bool> shadow;      // a baseline's second and later copies: run for pairing, no summary row
};

// The case's baseline values: NAME=VALUE;... in the parameters' order of `baseline`.
std::string baseline_text(const std::map<std::string, std::string>& baseline);

// Whether the case has every value of the baseline (is a baseline case).
bool has_baseline_values(const ParamSet& p, const std::map<std::string, std::string>& baseline);

// Whether `base` is the baseline of `c`: it has the baseline's values, and every other parameter both use
// has the same value in both.
bool is_baseline_of(const ParamSet& base, const ParamSet& c, const std::map<std::string, std::string>& baseline);

// Splits `cases` into groups of at most `size`. Without a baseline (or with size < 2: nothing can pair):
// consecutive chunks. With one: each baseline case with its dependents, size - 1 of them per group, the
// baseline in every group (a shadow after the first); the cases without a baseline in chunks after them.
std::vector<GroupPlan> plan_groups(const std::vector<ParamSet>& cases,
                                   const std::map<std::string, std::string>& baseline, size_t size);

}  // namespace oitbench
