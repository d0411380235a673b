#include "core/grid.hpp"

#include <algorithm>
#include <set>
#include <sstream>
#include <unordered_map>

namespace oitbench {

namespace {
std::string fmt_count(double v) {
  std::ostringstream s;
  s.precision(15);
  s << v;
  return s.str();
}
}  // namespace

CaseGrid::CaseGrid(std::vector<ParamSpec> specs, const std::map<std::string, std::vector<std::string>>& overrides,
                   bool quick, size_t max_cases)
    : specs_(std::move(specs)) {
  double product = 1;  // scoping only shrinks it
  for (const auto& spec : specs_) {
    auto it = overrides.find(spec.name);
    overridden_.push_back(it != overrides.end());
    values_.push_back(it != overrides.end() ? it->second : (quick && !spec.quick.empty()) ? spec.quick : spec.defaults);
    product *= static_cast<double>(std::max<size_t>(values_.back().size(), 1));
  }
  if (product > static_cast<double>(max_cases))
    throw UsageError("the parameter grid has " + fmt_count(product) + " cases, more than " + std::to_string(max_cases) +
                     "; narrow a --set list, or raise --max-cases");
  for (const auto& v : values_) {
    raw_size_ *= v.size();
    std::vector<int> first(v.size());
    std::unordered_map<std::string, int> seen;  // a --set list may hold 100,000 values
    for (size_t k = 0; k < v.size(); ++k) first[k] = seen.emplace(v[k], static_cast<int>(k)).first->second;
    first_equal_.push_back(std::move(first));
  }
  for (const auto& spec : specs_) {
    std::vector<Condition> conds;
    for (const auto& c : spec.applies_when) {
      Condition cond;
      cond.param = index_of(c.param);
      if (cond.param >= 0) {
        const auto p = static_cast<size_t>(cond.param);
        auto in = [&](const std::string& v) {
          return std::find(c.values.begin(), c.values.end(), v) != c.values.end();
        };
        cond.holds.push_back(!specs_[p].defaults.empty() && in(specs_[p].defaults.front()));
        for (const auto& v : values_[p]) cond.holds.push_back(in(v));
      }
      conds.push_back(std::move(cond));
    }
    conditions_.push_back(std::move(conds));
    std::vector<long> reads;
    for (const auto& name : spec.applies_if_reads) reads.push_back(index_of(name));
    reads_.push_back(std::move(reads));
  }
  for (size_t i = 0; i < specs_.size(); ++i) {
    for (size_t k = 0; k < values_[i].size(); ++k) all_cases_ = all_cases_ && first_equal_[i][k] == static_cast<int>(k);
    all_cases_ = all_cases_ && (!scoped(i) || values_[i].size() <= 1);
  }
}

long CaseGrid::index_of(const std::string& name) const {
  for (size_t i = 0; i < specs_.size(); ++i)
    if (specs_[i].name == name) return static_cast<long>(i);
  return -1;
}

const std::string& CaseGrid::value(size_t spec, int digit) const {
  return digit == kDefault ? specs_[spec].defaults.front() : values_[spec][static_cast<size_t>(digit)];
}

void CaseGrid::decode(uint64_t raw, std::vector<int>& digit) const {
  digit.resize(specs_.size());
  for (size_t i = specs_.size(); i-- > 0;) {
    const uint64_t n = values_[i].size();
    digit[i] = static_cast<int>(raw % n);
    raw /= n;
  }
}

uint64_t CaseGrid::encode(const std::vector<int>& digit) const {
  uint64_t raw = 0;
  for (size_t i = 0; i < specs_.size(); ++i) raw = raw * values_[i].size() + static_cast<uint64_t>(digit[i]);
  return raw;
}

ParamSet CaseGrid::to_params(const State& s) const {
  std::vector<std::pair<std::string, std::string>> values;
  values.reserve(specs_.size());
  for (size_t i = 0; i < specs_.size(); ++i) values.emplace_back(specs_[i].name, value(i, s.digit[i]));
  ParamSet p(std::move(values));
  for (size_t i = 0; i < specs_.size(); ++i)
    if (!s.used[i]) p.mark_unused(specs_[i].name);
  return p;
}

// ParamSpec::applies on the case as scoping has left it so far (the parameters before `spec` already
// at their defaults where they do not apply), as expand_grid always read it.
bool CaseGrid::applies(size_t spec, const State& s) const {
  for (const auto& c : conditions_[spec]) {
    if (c.param < 0) return false;
    if (!c.holds[static_cast<size_t>(s.digit[static_cast<size_t>(c.param)] + 1)]) return false;
  }
  const ParamSpec& p = specs_[spec];
  if (!p.applies_if) return true;
  if (p.applies_if_reads.empty()) return p.applies_if(to_params(s));  // reads anything: the whole case
  std::pair<size_t, std::vector<int>> key{spec, {}};
  for (const long r : reads_[spec]) key.second.push_back(r < 0 ? -2 : s.digit[static_cast<size_t>(r)]);
  if (auto it = predicate_cache_.find(key); it != predicate_cache_.end()) return it->second;
  std::vector<std::pair<std::string, std::string>> read;
  for (size_t k = 0; k < reads_[spec].size(); ++k)
    if (const long r = reads_[spec][k]; r >= 0)
      read.emplace_back(p.applies_if_reads[k], value(static_cast<size_t>(r), s.digit[static_cast<size_t>(r)]));
  return predicate_cache_[key] = p.applies_if(ParamSet(std::move(read)));
}

void CaseGrid::scope(State& s) const {
  s.used.assign(specs_.size(), 1);
  for (size_t i = 0; i < specs_.size(); ++i) {
    if (applies(i, s)) continue;
    s.used[i] = 0;
    if (!specs_[i].defaults.empty()) s.digit[i] = kDefault;
  }
}

bool CaseGrid::same_case(const State& a, const State& b) const {
  for (size_t i = 0; i < specs_.size(); ++i) {
    if (a.used[i] != b.used[i]) return false;
    if (a.used[i] && value(i, a.digit[i]) != value(i, b.digit[i])) return false;
  }
  return true;
}

// A smaller number that scopes to the same case as `raw` (scoped: `s`): it has the same values where
// the case uses a parameter, anything elsewhere. Walked in increasing order; reached only where the
// first such number (every other parameter at its first value) scopes differently.
bool CaseGrid::earlier_twin(uint64_t raw, const State& s) const {
  std::vector<int> raw_digit;
  decode(raw, raw_digit);
  std::vector<std::vector<int>> choices(specs_.size());
  for (size_t i = 0; i < specs_.size(); ++i)
    for (size_t k = 0; k < values_[i].size(); ++k)
      if (!s.used[i] || first_equal_[i][k] == first_equal_[i][static_cast<size_t>(raw_digit[i])])
        choices[i].push_back(static_cast<int>(k));
  std::vector<size_t> at(specs_.size(), 0);
  State t;
  for (;;) {
    t.digit.resize(specs_.size());
    for (size_t i = 0; i < specs_.size(); ++i) t.digit[i] = choices[i][at[i]];
    if (encode(t.digit) >= raw) return false;
    scope(t);
    if (same_case(s, t)) return true;
    size_t i = specs_.size();
    while (i-- > 0 && ++at[i] == choices[i].size()) at[i] = 0;
    if (i == static_cast<size_t>(-1)) return false;
  }
}

bool CaseGrid::is_case(uint64_t raw) const {
  if (raw >= raw_size_) return false;
  if (all_cases_) return true;
  State s;
  decode(raw, s.digit);
  scope(s);
  State first;  // the smallest number that can be the same case
  first.digit.resize(specs_.size());
  for (size_t i = 0; i < specs_.size(); ++i)
    first.digit[i] = s.used[i] ? first_equal_[i][static_cast<size_t>(s.digit[i])] : 0;
  if (encode(first.digit) == raw) return true;
  scope(first);
  if (same_case(s, first)) return false;
  return !earlier_twin(raw, s);
}

uint64_t CaseGrid::next_case(uint64_t raw) const {
  while (raw < raw_size_ && !is_case(raw)) ++raw;
  return std::min(raw, raw_size_);
}

ParamSet CaseGrid::case_at(uint64_t raw) const {
  State s;
  decode(raw, s.digit);
  scope(s);
  return to_params(s);
}

size_t CaseGrid::count() const {
  if (all_cases_) return static_cast<size_t>(raw_size_);
  if (count_ < 0) {
    long long n = 0;
    for (uint64_t raw = 0; raw < raw_size_; ++raw) n += is_case(raw) ? 1 : 0;
    count_ = n;
  }
  return static_cast<size_t>(count_);
}

void CaseGrid::for_each(const std::function<bool(const ParamSet&)>& fn) const {
  for (uint64_t raw = next_case(0); raw < raw_size_; raw = next_case(raw + 1))
    if (!fn(case_at(raw))) return;
}

std::vector<ParamSet> CaseGrid::cases() const {
  std::vector<ParamSet> out;
  for_each([&](const ParamSet& c) {
    out.push_back(c);
    return true;
  });
  return out;
}

void CaseGrid::check_overrides_apply() const {
  std::vector<size_t> open;  // overridden parameters not yet seen applying
  for (size_t i = 0; i < specs_.size(); ++i)
    if (overridden_[i]) open.push_back(i);
  State s;
  for (uint64_t raw = 0; raw < raw_size_ && !open.empty(); ++raw) {
    decode(raw, s.digit);
    scope(s);
    open.erase(std::remove_if(open.begin(), open.end(), [&](size_t i) { return s.used[i] != 0; }), open.end());
  }
  if (open.empty()) return;
  const ParamSpec& spec = specs_[open.front()];
  std::string selected;  // the values the scoping conditions saw, over every number
  for (const auto& cond : spec.applies_when) {
    const long p = index_of(cond.param);
    std::set<std::string> vals;
    for (uint64_t raw = 0; p >= 0 && raw < raw_size_; ++raw) {
      decode(raw, s.digit);
      scope(s);
      vals.insert(value(static_cast<size_t>(p), s.digit[static_cast<size_t>(p)]));
    }
    std::string list;
    for (const auto& v : vals) list += (list.empty() ? "" : ",") + v;
    selected += (selected.empty() ? "" : ", ") + cond.param + "=" + list;
  }
  throw UsageError("parameter '" + spec.name + "' applies only where " + spec.scope_text() +
                   "; no selected case has that" + (selected.empty() ? "" : " (" + selected + ")"));
}

// Parameters no scope touches take every value of their lists in some case (scoping changes only the
// scoped ones): their combinations are the product of their lists, in the grid's order.
std::vector<ParamSet> CaseGrid::distinct_product(const std::vector<std::string>& names) const {
  std::vector<size_t> at;  // the named parameters in the grid's order
  for (size_t i = 0; i < specs_.size(); ++i)
    if (std::find(names.begin(), names.end(), specs_[i].name) != names.end()) at.push_back(i);
  std::vector<ParamSet> out;
  if (raw_size_ == 0) return out;
  std::vector<size_t> digit(at.size(), 0);
  for (;;) {
    bool first = true;  // a repeated value's combinations are its first's
    for (size_t k = 0; k < at.size(); ++k) first = first && first_equal_[at[k]][digit[k]] == static_cast<int>(digit[k]);
    if (first) {
      std::vector<std::pair<std::string, std::string>> values;
      for (const auto& n : names)
        for (size_t k = 0; k < at.size(); ++k)
          if (specs_[at[k]].name == n) values.emplace_back(n, values_[at[k]][digit[k]]);
      out.emplace_back(std::move(values));
    }
    size_t k = at.size();
    while (k-- > 0 && ++digit[k] == values_[at[k]].size()) digit[k] = 0;
    if (k == static_cast<size_t>(-1)) return out;
  }
}

std::vector<ParamSet> CaseGrid::distinct(const std::vector<std::string>& names) const {
  std::vector<long> at;
  for (const auto& n : names) at.push_back(index_of(n));
  if (std::all_of(at.begin(), at.end(), [&](long i) { return i >= 0 && !scoped(static_cast<size_t>(i)); }))
    return distinct_product(names);
  std::set<std::vector<int>> seen;
  std::vector<ParamSet> out;
  State s;
  // The first number of each combination is a case: its smallest twin has the same values.
  for (uint64_t raw = 0; raw < raw_size_; ++raw) {
    decode(raw, s.digit);
    scope(s);
    std::vector<int> key;
    std::vector<std::pair<std::string, std::string>> values;
    for (size_t k = 0; k < at.size(); ++k) {
      if (at[k] < 0) continue;
      const auto i = static_cast<size_t>(at[k]);
      key.push_back(s.digit[i] == kDefault ? kDefault : first_equal_[i][static_cast<size_t>(s.digit[i])]);
      values.emplace_back(names[k], value(i, s.digit[i]));
    }
    if (seen.insert(key).second) out.emplace_back(std::move(values));
  }
  return out;
}

bool CaseGrid::has_case_with(const std::map<std::string, std::string>& values) const {
  std::vector<std::pair<size_t, std::string>> want;
  for (const auto& [name, v] : values) {
    const long i = index_of(name);
    if (i < 0) return values.empty();
    want.emplace_back(static_cast<size_t>(i), v);
  }
  State s;
  for (uint64_t raw = 0; raw < raw_size_; ++raw) {
    decode(raw, s.digit);
    scope(s);
    if (std::all_of(want.begin(), want.end(),
                    [&](const auto& w) { return value(w.first, s.digit[w.first]) == w.second; }))
      return true;
  }
  return false;
}

}  // namespace oitbench
