#include "core/params.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "core/grid.hpp"

namespace oitbench {

namespace {
std::string fmt_num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}
bool parse_number(const std::string& v, bool integer, double& out) {
  if (v.empty()) return false;
  try {
    size_t pos = 0;
    if (integer) {
      long long x = 0;
      if (!parse_exact_integer(v, x)) return false;
      out = static_cast<double>(x);
      pos = v.size();
    } else {
      out = std::stod(v, &pos);
    }
    return pos == v.size() && std::isfinite(out);
  } catch (const std::exception&) {
    return false;
  }
}
}  // namespace

ParamSpec ParamSpec::choice(std::string name, std::string description, std::vector<std::string> allowed,
                            std::vector<std::string> defaults, std::vector<std::string> quick) {
  if (defaults.empty()) defaults = allowed;
  return {std::move(name), std::move(description), std::move(defaults), std::move(quick), std::move(allowed)};
}

ParamSpec ParamSpec::integer(std::string name, std::string description, double min, double max,
                             std::vector<std::string> defaults, std::vector<std::string> quick) {
  return {std::move(name), std::move(description), std::move(defaults), std::move(quick), {}, Kind::Integer, min, max};
}

ParamSpec ParamSpec::text(std::string name, std::string description, std::vector<std::string> defaults,
                          std::vector<std::string> quick) {
  return {std::move(name), std::move(description), std::move(defaults), std::move(quick), {}};
}

bool parse_exact_integer(const std::string& v, long long& out) {
  if (v.empty() || v.size() > 24) return false;
  size_t i = v[0] == '-' || v[0] == '+' ? 1 : 0;
  if (i == v.size() || v.find_first_not_of("0123456789", i) != std::string::npos) return false;
  try {
    size_t pos = 0;
    long long x = std::stoll(v, &pos);
    if (pos != v.size() || x > kMaxExactInteger || x < -kMaxExactInteger) return false;
    out = x;
    return true;
  } catch (const std::exception&) {  // past long long
    return false;
  }
}

// An integer parameter without bounds of its own lands in an int: its range is the int's.
double ParamSpec::lowest() const {
  return kind == Kind::Integer && min <= -1e300 ? static_cast<double>(std::numeric_limits<int>::min()) : min;
}
double ParamSpec::highest() const {
  return kind == Kind::Integer && max >= 1e300 ? static_cast<double>(std::numeric_limits<int>::max()) : max;
}

std::string ParamSpec::allowed_text() const {
  if (!allowed.empty()) {
    std::string s;
    for (const auto& a : allowed) s += (s.empty() ? "" : "|") + a;
    return s;
  }
  if (kind == Kind::Text) return "any text";
  std::string s = kind == Kind::Integer ? "integer" : "number";
  auto bound = [&](double v) {  // an integer's bounds in full: 2147483647, not 2.14748e+09
    return kind == Kind::Integer ? std::to_string(static_cast<long long>(v)) : fmt_num(v);
  };
  if (lowest() > -1e300 || highest() < 1e300) s += " in [" + bound(lowest()) + ", " + bound(highest()) + "]";
  return s;
}

void ParamSpec::check(const std::string& value, const std::string& experiment) const {
  if (!allowed.empty()) {
    if (std::find(allowed.begin(), allowed.end(), value) == allowed.end())
      throw UsageError("experiment '" + experiment + "': invalid value '" + value + "' for parameter '" + name +
                       "'; valid values: " + allowed_text());
    return;
  }
  if (kind == Kind::Text) return;
  double v = 0;
  if (!parse_number(value, kind == Kind::Integer, v) || v < lowest() || v > highest())
    throw UsageError("experiment '" + experiment + "': invalid value '" + value + "' for parameter '" + name +
                     "'; expected " + allowed_text());
}

bool ParamSpec::applies(const ParamSet& p) const {
  for (const auto& c : applies_when) {
    if (!p.has(c.param)) return false;
    const auto& v = p.get(c.param);
    if (std::find(c.values.begin(), c.values.end(), v) == c.values.end()) return false;
  }
  return !applies_if || applies_if(p);
}

std::string ParamSpec::scope_text() const {
  std::string s;
  for (const auto& c : applies_when) {
    std::string values;
    for (const auto& v : c.values) values += (values.empty() ? "" : ", ") + v;
    s += (s.empty() ? "" : " and ") + c.param + " in {" + values + "}";
  }
  if (applies_if) s += (s.empty() ? "" : " and ") + applies_if_text;
  return s;
}

std::vector<std::pair<std::string, std::string>> ParamSet::used_values() const {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& kv : values_)
    if (!unused_.count(kv.first)) out.push_back(kv);
  return out;
}

const std::string& ParamSet::get(const std::string& name) const {
  for (const auto& [k, v] : values_)
    if (k == name) return v;
  throw std::out_of_range("case has no parameter '" + name + "'");
}
bool ParamSet::has(const std::string& name) const {
  return std::any_of(values_.begin(), values_.end(), [&](const auto& kv) { return kv.first == name; });
}
long long ParamSet::get_int(const std::string& name) const { return std::stoll(get(name)); }
double ParamSet::get_double(const std::string& name) const { return std::stod(get(name)); }
void ParamSet::set(const std::string& name, const std::string& value) {
  for (auto& [k, v] : values_)
    if (k == name) {
      v = value;
      return;
    }
  values_.emplace_back(name, value);
}
std::string ParamSet::describe() const {
  std::string s;
  for (const auto& [k, v] : used_values()) s += (s.empty() ? "" : " ") + k + "=" + v;
  return s;
}

std::pair<std::string, std::vector<std::string>> parse_set_option(const std::string& text) {
  auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0) throw UsageError("--set expects NAME=V1,V2,... (got '" + text + "')");
  std::string name = text.substr(0, eq);
  std::vector<std::string> values;
  std::stringstream ss(text.substr(eq + 1));
  std::string item;
  while (std::getline(ss, item, ',')) {
    auto dots = item.find("..");
    if (dots != std::string::npos) {
      long long a = 0, b = 0, step = 1;
      std::string rest = item.substr(dots + 2);
      auto colon = rest.find(':');
      bool ok = parse_exact_integer(item.substr(0, dots), a) && parse_exact_integer(rest.substr(0, colon), b) &&
                (colon == std::string::npos || parse_exact_integer(rest.substr(colon + 1), step));
      if (!ok || step <= 0 || b < a)
        throw UsageError("--set " + name + ": bad range '" + item +
                         "' (expected A..B or A..B:STEP with integers A<=B and STEP>0, each of magnitude at most "
                         "2^53 = " +
                         std::to_string(kMaxExactInteger) + ")");
      // |a|, |b| <= 2^53: the difference cannot overflow, and the count is exact.
      const long long count = (b - a) / step + 1;
      if (count > static_cast<long long>(kMaxRangeValues) ||
          values.size() + static_cast<size_t>(count) > kMaxRangeValues)
        throw UsageError("--set " + name + ": range '" + item + "' has " + std::to_string(count) +
                         " values; a --set list may have at most " + std::to_string(kMaxRangeValues));
      for (long long k = 0; k < count; ++k) values.push_back(std::to_string(a + k * step));
    } else if (!item.empty()) {
      values.push_back(item);
    }
    if (values.size() > kMaxRangeValues)
      throw UsageError("--set " + name + ": more than " + std::to_string(kMaxRangeValues) + " values");
  }
  if (values.empty()) throw UsageError("--set " + name + ": no values given");
  return {name, values};
}

std::map<std::string, std::vector<std::string>> parse_set_options(const std::vector<std::string>& texts,
                                                                  const std::string& option) {
  std::map<std::string, std::vector<std::string>> out;
  for (const auto& t : texts) {
    auto [name, values] = parse_set_option(t);
    if (out.count(name))
      throw UsageError(option + " " + name + " is given twice; give one list instead (" + option + " " + name +
                       "=A,B,...)");
    out[name] = std::move(values);
  }
  return out;
}

std::vector<ParamSet> expand_grid(const std::vector<ParamSpec>& specs,
                                  const std::map<std::string, std::vector<std::string>>& overrides, bool quick,
                                  size_t max_cases) {
  const CaseGrid grid(specs, overrides, quick, max_cases);
  grid.check_overrides_apply();
  return grid.cases();
}

}  // namespace oitbench
