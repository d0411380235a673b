#pragma once
// A parameter grid that is never held in memory: the product of the value lists is numbered in mixed
// radix (the last parameter fastest: the order the cases always ran in), and a number is decoded into
// its case only when that case is needed. Scoping (ParamSpec::applies_when, applies_if) and the dedupe
// of cases that agree on every parameter they use are decided from the number: a number is a case when
// no smaller number scopes to the same case (usually: when every parameter the case does not use sits at
// its first value). Counting and checking walk the numbers without building a case, so the memory is
// the value lists' whatever the number of cases (docs/usage.md#large-grids).
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "core/params.hpp"

namespace oitbench {

class CaseGrid {
 public:
  // An override list replaces that parameter's defaults (or quick grid). Throws UsageError when the
  // product of the value counts exceeds `max_cases`, before anything is walked.
  CaseGrid(std::vector<ParamSpec> specs, const std::map<std::string, std::vector<std::string>>& overrides, bool quick,
           size_t max_cases = kMaxGridCases);

  // The product of the value counts: the numbers 0..raw_size()-1, some of which repeat an earlier case.
  uint64_t raw_size() const { return raw_size_; }
  // Whether number `raw` is a case (no smaller number scopes to the same one).
  bool is_case(uint64_t raw) const;
  // The first case's number at or after `raw`; raw_size() when there is none.
  uint64_t next_case(uint64_t raw) const;
  // The case of number `raw` (every parameter, those it does not use at their first default).
  ParamSet case_at(uint64_t raw) const;
  // The number of cases (walked once, then kept).
  size_t count() const;
  // Every case in order until `fn` returns false.
  void for_each(const std::function<bool(const ParamSet&)>& fn) const;
  // Every case, in memory: small grids and tests only.
  std::vector<ParamSet> cases() const;

  // Throws UsageError for an override that applies to no case ("parameter 'nodes' applies only where
  // ..."), as expand_grid always did.
  void check_overrides_apply() const;
  // One case per distinct combination of the values of `names` over the grid's cases, holding only those
  // parameters, in the order they first occur: what Experiment::check_cases reads.
  std::vector<ParamSet> distinct(const std::vector<std::string>& names) const;
  // Whether some case has every value of `values` (a baseline: core/groups.hpp).
  bool has_case_with(const std::map<std::string, std::string>& values) const;

  const std::vector<ParamSpec>& specs() const { return specs_; }

 private:
  // A case being scoped: per parameter, the index of its value in its list, or kDefault where it does
  // not apply and runs at its first default; and whether it applies.
  static constexpr int kDefault = -1;
  struct State {
    std::vector<int> digit;
    std::vector<char> used;
  };
  void decode(uint64_t raw, std::vector<int>& digit) const;
  uint64_t encode(const std::vector<int>& digit) const;
  void scope(State& s) const;
  bool applies(size_t spec, const State& s) const;
  bool same_case(const State& a, const State& b) const;
  bool scoped(size_t spec) const { return !specs_[spec].applies_when.empty() || specs_[spec].applies_if; }
  std::vector<ParamSet> distinct_product(const std::vector<std::string>& names) const;
  bool earlier_twin(uint64_t raw, const State& s) const;
  const std::string& value(size_t spec, int digit) const;
  ParamSet to_params(const State& s) const;
  long index_of(const std::string& name) const;

  std::vector<ParamSpec> specs_;
  std::vector<std::vector<std::string>> values_;
  std::vector<char> overridden_;               // a list given for it (--set, a preset): it must apply to some case
  std::vector<std::vector<int>> first_equal_;  // per value: the first index in its list with the same text
  // per parameter, per condition: which of the condition parameter's values (index + 1; 0 the default) hold
  struct Condition {
    long param = -1;  // -1: not a parameter of the grid (never holds)
    std::vector<char> holds;
  };
  std::vector<std::vector<Condition>> conditions_;
  std::vector<std::vector<long>> reads_;  // applies_if's parameters (ParamSpec::applies_if_reads)
  // applies_if's answers by parameter and the digits it reads: a scene is loaded once, not once a case
  mutable std::map<std::pair<size_t, std::vector<int>>, bool> predicate_cache_;
  uint64_t raw_size_ = 1;
  // Every number is a case: no list repeats a value and no scoped parameter has more than one (the usual
  // grid), so nothing is walked to count or find them.
  bool all_cases_ = true;
  mutable long long count_ = -1;
};

}  // namespace oitbench
