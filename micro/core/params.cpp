#include "core/params.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

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
      long long x = std::stoll(v, &pos);
      out = static_cast<double>(x);
    } else {
      out = std::stod(v, &pos);
    }
    return pos == v.size() && std::isfinite(out);
  } catch (const std::exception&) {
    return false;
  }
}
}  // namespace

std::string ParamSpec::allowed_text() const {
  if (!allowed.empty()) {
    std::string s;
    for (const auto& a : allowed) s += (s.empty() ? "" : "|") + a;
    return s;
  }
  if (kind == Kind::Text) return "any text";
  std::string s = kind == Kind::Integer ? "integer" : "number";
  if (min > -1e300 || max < 1e300) s += " in [" + fmt_num(min) + ", " + fmt_num(max) + "]";
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
  if (!parse_number(value, kind == Kind::Integer, v) || v < min || v > max)
    throw UsageError("experiment '" + experiment + "': invalid value '" + value + "' for parameter '" + name +
                     "'; expected " + allowed_text());
}

bool ParamSpec::applies(const ParamSet& p) const {
  for (const auto& c : applies_when) {
    if (!p.has(c.param)) return false;
    const auto& v = p.get(c.param);
    if (std::find(c.values.begin(), c.values.end(), v) == c.values.end()) return false;
  }
  return true;
}

std::string ParamSpec::scope_text() const {
  std::string s;
  for (const auto& c : applies_when) {
    std::string values;
    for (const auto& v : c.values) values += (values.empty() ? "" : ", ") + v;
    s += (s.empty() ? "" : " and ") + c.param + " in {" + values + "}";
  }
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
      double a = 0, b = 0, step = 1;
      std::string rest = item.substr(dots + 2);
      auto colon = rest.find(':');
      bool ok = parse_number(item.substr(0, dots), true, a) && parse_number(rest.substr(0, colon), true, b) &&
                (colon == std::string::npos || parse_number(rest.substr(colon + 1), true, step));
      if (!ok || step <= 0 || b < a)
        throw UsageError("--set " + name + ": bad range '" + item + "' (expected A..B or A..B:STEP with A<=B)");
      if ((b - a) / step > 100000) throw UsageError("--set " + name + ": range '" + item + "' has too many values");
      for (double x = a; x <= b; x += step) values.push_back(std::to_string(static_cast<long long>(x)));
    } else if (!item.empty()) {
      values.push_back(item);
    }
  }
  if (values.empty()) throw UsageError("--set " + name + ": no values given");
  return {name, values};
}

std::vector<ParamSet> expand_grid(const std::vector<ParamSpec>& specs,
                                  const std::map<std::string, std::vector<std::string>>& overrides, bool quick) {
  auto values_of = [&](const ParamSpec& spec) -> const std::vector<std::string>& {
    auto it = overrides.find(spec.name);
    return it != overrides.end() ? it->second : (quick && !spec.quick.empty()) ? spec.quick : spec.defaults;
  };
  // Bound the work before building it: the product of the value counts (scoping only shrinks it).
  double product = 1;
  for (const auto& spec : specs) product *= static_cast<double>(std::max<size_t>(values_of(spec).size(), 1));
  if (product > static_cast<double>(kMaxGridCases))
    throw UsageError("the parameter grid has " + fmt_num(product) + " cases, more than " +
                     std::to_string(kMaxGridCases) + "; narrow a --set list");
  std::vector<ParamSet> out{ParamSet{}};
  for (const auto& spec : specs) {
    const auto& values = values_of(spec);
    std::vector<ParamSet> next;
    next.reserve(out.size() * values.size());
    for (const auto& base : out)
      for (const auto& v : values) {
        auto c = base;
        c.set(spec.name, v);
        next.push_back(std::move(c));
      }
    out = std::move(next);
  }
  // Scoping, in spec order: a condition reads parameters declared before or after the scoped one.
  std::vector<ParamSet> cases;
  std::set<std::vector<std::pair<std::string, std::string>>> seen;
  std::set<std::string> applied;
  for (auto& c : out) {
    for (const auto& spec : specs) {
      if (spec.applies(c)) {
        applied.insert(spec.name);
      } else {
        if (!spec.defaults.empty()) c.set(spec.name, spec.defaults.front());
        c.mark_unused(spec.name);
      }
    }
    if (seen.insert(c.used_values()).second) cases.push_back(c);
  }
  for (const auto& spec : specs)
    if (overrides.count(spec.name) && !applied.count(spec.name)) {
      std::string selected;
      for (const auto& cond : spec.applies_when) {
        std::set<std::string> vals;
        for (const auto& c : out) vals.insert(c.get(cond.param));
        std::string list;
        for (const auto& v : vals) list += (list.empty() ? "" : ",") + v;
        selected += (selected.empty() ? "" : ", ") + cond.param + "=" + list;
      }
      throw UsageError("parameter '" + spec.name + "' applies only where " + spec.scope_text() +
                       "; no selected case has that (" + selected + ")");
    }
  return cases;
}

}  // namespace oitbench
