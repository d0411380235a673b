#include "viewer/oit_settings.hpp"

#include <algorithm>

#include "oit/techniques.hpp"

namespace oitbench::viewer {

namespace {
constexpr const char* kExperiment = "oit";
}  // namespace

OitSettings::OitSettings(Registry& registry, const std::map<std::string, std::string>& chosen) {
  experiment_ = registry.find(kExperiment);
  if (!experiment_) throw UsageError("this build has no '" + std::string(kExperiment) + "' experiment");
  specs_ = registry.params_of(*experiment_);
  std::vector<std::pair<std::string, std::string>> values;
  for (const auto& s : specs_) values.emplace_back(s.name, s.defaults.empty() ? "" : s.defaults.front());
  params_ = ParamSet(std::move(values));
  for (const auto& [name, value] : chosen) set(name, value);
}

const ParamSpec& OitSettings::spec(const std::string& name) const {
  for (const auto& s : specs_)
    if (s.name == name) return s;
  std::string names;
  for (const auto& s : specs_) names += (names.empty() ? "" : ", ") + s.name;
  throw UsageError("experiment '" + std::string(kExperiment) + "' has no parameter '" + name +
                   "'; parameters: " + names);
}

bool OitSettings::has_param(const std::string& name) const {
  return std::any_of(specs_.begin(), specs_.end(), [&](const ParamSpec& s) { return s.name == name; });
}

void OitSettings::set(const std::string& name, const std::string& value) {
  spec(name).check(value, kExperiment);
  params_.set(name, value);
}

// What the current technique is and reads, from the technique table (micro/oit/techniques.hpp).
bool OitSettings::is_exact() const {
  const oit::Technique* t = oit::find_technique(technique());
  return t && t->family == oit::TechniqueFamily::Exact;
}

bool OitSettings::uses_max_frags() const {
  const oit::Technique* t = oit::find_technique(technique());
  return t && t->reads("max_frags");
}

bool OitSettings::uses_nodes() const {
  const oit::Technique* t = oit::find_technique(technique());
  return t && t->reads("nodes") && has_param("nodes");
}

std::string OitSettings::step_technique(int step, bool& changed) {
  const auto& all = spec("technique").allowed;
  auto it = std::find(all.begin(), all.end(), technique());
  long i = it == all.end() ? 0 : it - all.begin();
  long n = static_cast<long>(all.size());
  set("technique", all[static_cast<size_t>(((i + step) % n + n) % n)]);
  changed = true;
  return "technique " + technique();
}

std::string OitSettings::toggle_bma(bool& changed) {
  changed = false;
  const oit::Technique* t = oit::find_technique(technique());
  if (const oit::Technique* twin = t ? oit::bma_twin(*t) : nullptr) {
    set("technique", twin->name);
    changed = true;
    return "technique " + technique();
  }
  return "B: " + technique() + " has no BASE/BMA twin (B toggles a BASE resolve and its BMA form)";
}

std::string OitSettings::scale_max_frags(bool up, unsigned in_use, bool& changed) {
  changed = false;
  if (uses_nodes()) {
    const ParamSpec& s = spec("nodes");
    long long n = params_.get_int("nodes");
    long long next =
        std::clamp<long long>(up ? n * 2 : n / 2, static_cast<long long>(s.min), static_cast<long long>(s.max));
    if (next == n) return "nodes " + std::to_string(n) + " is the " + (up ? "largest" : "smallest") + " allowed";
    set("nodes", std::to_string(next));
    changed = true;
    return "nodes " + std::to_string(next);
  }
  if (!uses_max_frags()) return "M: " + technique() + " has no MAX_FRAGS";
  const ParamSpec& s = spec("max_frags");
  long long v = params_.get_int("max_frags");
  long long current = v > 0 ? v : std::max(1u, in_use);
  long long next = up ? current * 2 : current / 2;
  if (!up && v == 1) next = 0;  // below 1: back to auto
  if (next > static_cast<long long>(s.max)) return "MAX_FRAGS " + std::to_string(current) + " is the largest allowed";
  if (next == v) return "MAX_FRAGS is already auto";
  set("max_frags", std::to_string(next));
  changed = true;
  return next == 0 ? std::string("MAX_FRAGS auto") : "MAX_FRAGS " + std::to_string(next);
}

std::string OitSettings::step_capture(bool& changed) {
  changed = false;
  const auto& all = spec("capture").allowed;
  if (all.size() < 2) return "C: the only capture storage is " + get("capture");
  auto it = std::find(all.begin(), all.end(), get("capture"));
  size_t i = it == all.end() ? 0 : static_cast<size_t>(it - all.begin());
  set("capture", all[(i + 1) % all.size()]);
  changed = true;
  return "capture storage " + get("capture");
}

}  // namespace oitbench::viewer
