#include "core/presets.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>

#include "core/data_dirs.hpp"
#include "core/files.hpp"
#include "core/text_position.hpp"

namespace oitbench {

namespace {

// Where a preset is wrong: FILE:LINE:COLUMN: runs[2].hardware.reps: what was expected.
class PresetText {
 public:
  PresetText(const std::string& path, const std::string& text) : path_(path), text_(text) {}
  UsageError error(const std::vector<std::string>& keys, const std::string& what) const {
    std::string where;
    for (const auto& k : keys)
      where +=
          !k.empty() && std::all_of(k.begin(), k.end(), ::isdigit) ? "[" + k + "]" : (where.empty() ? "" : ".") + k;
    return UsageError(path_ + ":" + line_column(text_, json_path_offset(text_, keys)) + ": " +
                      (where.empty() ? "" : where + ": ") + what);
  }

 private:
  const std::string& path_;
  const std::string& text_;
};

std::string to_value(const nlohmann::json& v, const PresetText& at, const std::vector<std::string>& keys) {
  if (v.is_string()) return v.get<std::string>();
  if (v.is_number_integer()) return std::to_string(v.get<long long>());
  if (v.is_number()) {
    std::ostringstream s;
    s << v.get<double>();
    return s.str();
  }
  throw at.error(keys,
                 "expected a string or a number, got " + std::string(v.type_name()) +
                     (v.is_boolean() ? " (write a parameter's value as the command line would, e.g. \"1\")" : ""));
}

Resolution resolution_value(const nlohmann::json& v, const PresetText& at, const std::vector<std::string>& keys) {
  if (!v.is_string()) throw at.error(keys, "expected \"WIDTHxHEIGHT\", got " + std::string(v.type_name()));
  try {
    return parse_resolution(v.get<std::string>());
  } catch (const UsageError& e) {
    throw at.error(keys, e.what());
  }
}

int count_value(const nlohmann::json& v, const PresetText& at, const std::vector<std::string>& keys, int min) {
  if (!v.is_number_integer() || v.get<long long>() < min || v.get<long long>() > 100000)
    throw at.error(keys, std::string("expected a ") + (min > 0 ? "positive" : "non-negative") +
                             " integer (at most 100000), got " +
                             (v.is_string() ? "\"" + v.get<std::string>() + "\"" : v.dump()));
  return v.get<int>();
}

// "set": {"NAME": [V1, V2, ...] or V, ...}: parameter lists.
std::map<std::string, std::vector<std::string>> set_lists(const nlohmann::json& v, const PresetText& at,
                                                          std::vector<std::string> keys) {
  if (!v.is_object()) throw at.error(keys, "expected an object of parameter lists");
  std::map<std::string, std::vector<std::string>> lists;
  for (const auto& [pk, pv] : v.items()) {
    auto& list = lists[pk];
    keys.push_back(pk);
    if (pv.is_array()) {
      for (size_t n = 0; n < pv.size(); ++n) {
        keys.push_back(std::to_string(n));
        list.push_back(to_value(pv[n], at, keys));
        keys.pop_back();
      }
    } else {
      list.push_back(to_value(pv, at, keys));
    }
    if (list.empty()) throw at.error(keys, "empty value list");
    keys.pop_back();
  }
  return lists;
}

// "hardware": {"resolution": "1920x1080", "reps": 10, "warmup": 2, "set": {...}}: what changes on hardware
// drivers.
HardwareSizes hardware_sizes(const nlohmann::json& v, const PresetText& at, std::vector<std::string> keys) {
  if (!v.is_object() || v.empty())
    throw at.error(keys,
                   "expected an object with one or more of resolution, reps, warmup, set (what changes on "
                   "hardware drivers), got " +
                       (v.is_object() ? std::string("{}") : std::string(v.type_name())));
  HardwareSizes h;
  for (const auto& [k, x] : v.items()) {
    keys.push_back(k);
    if (k == "resolution")
      h.resolution = resolution_value(x, at, keys);
    else if (k == "reps")
      h.reps = count_value(x, at, keys, 1);
    else if (k == "warmup")
      h.warmup = count_value(x, at, keys, 0);
    else if (k == "set")
      h.set = set_lists(x, at, keys);
    else
      throw at.error(keys, "unknown key \"" + k + "\"; expected resolution, reps, warmup, set");
    keys.pop_back();
  }
  return h;
}

}  // namespace

Resolution parse_resolution(const std::string& text) {
  static const std::regex re(R"((\d+)x(\d+))");
  std::smatch m;
  if (text.size() > 64 || !std::regex_match(text, m, re))
    throw UsageError("resolution '" + text + "': expected WIDTHxHEIGHT, e.g. 800x600");
  auto side = [&](const std::string& digits) {  // past 16384 by its length alone: no overflow
    return digits.size() > 6 ? 1000000 : std::stoi(digits);
  };
  Resolution r{side(m[1]), side(m[2])};
  if (r.width < 1 || r.height < 1 || r.width > kMaxResolutionSide || r.height > kMaxResolutionSide)
    throw UsageError("resolution '" + text + "': each side must be in [1, " + std::to_string(kMaxResolutionSide) + "]");
  return r;
}

std::string default_preset_dir() { return data_dir("presets"); }

Preset parse_preset(const std::string& name, const std::string& path, const std::string& text) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw UsageError(path + ":" + line_column(text, e.byte > 0 ? e.byte - 1 : 0) + ": malformed JSON: " + e.what());
  } catch (const nlohmann::json::exception& e) {  // a number past a double's range (1e400)
    throw UsageError(path + ":" + line_column(text, json_error_offset(text, e.what())) + ": " + e.what());
  }
  const PresetText at(path, text);
  Preset p{name, "", path, {}};
  if (!j.is_object()) throw at.error({}, "expected a JSON object at the top level");
  if (j.contains("description")) {
    if (!j["description"].is_string()) throw at.error({"description"}, "expected a string");
    p.description = j["description"].get<std::string>();
  }
  for (const auto& [k, v] : j.items())
    if (k != "description" && k != "runs") throw at.error({k}, "unknown key \"" + k + "\"; expected description, runs");
  if (!j.contains("runs") || !j["runs"].is_array() || j["runs"].empty())
    throw at.error({"runs"}, "expected \"runs\": a non-empty array of {\"experiment\": ..., \"set\": {...}}");
  for (size_t i = 0; i < j["runs"].size(); ++i) {
    const auto& r = j["runs"][i];
    const std::vector<std::string> entry = {"runs", std::to_string(i)};
    auto in = [&](std::initializer_list<std::string> more) {
      auto keys = entry;
      keys.insert(keys.end(), more);
      return keys;
    };
    if (!r.is_object() || !r.contains("experiment") || !r["experiment"].is_string())
      throw at.error(entry, "expected an object with \"experiment\": \"NAME\"");
    RunRequest req;
    req.experiment = r["experiment"].get<std::string>();
    req.origin = path + ":" + line_column(text, json_path_offset(text, entry)) + ": runs[" + std::to_string(i) + "]";
    for (const auto& [k, v] : r.items()) {
      if (k == "experiment") continue;
      if (k == "set") {
        req.overrides = set_lists(v, at, in({"set"}));
      } else if (k == "resolution") {
        req.resolution = resolution_value(v, at, in({k}));
      } else if (k == "reps" || k == "warmup") {
        (k == "reps" ? req.reps : req.warmup) = count_value(v, at, in({k}), k == "reps" ? 1 : 0);
      } else if (k == "quick") {
        if (!v.is_boolean()) throw at.error(in({k}), "expected true or false");
        req.quick = v.get<bool>();
      } else if (k == "hardware") {
        req.hardware = hardware_sizes(v, at, in({k}));
        if (v.contains("set"))
          req.hardware->origin = path + ":" + line_column(text, json_path_offset(text, in({k, "set"}))) + ": runs[" +
                                 std::to_string(i) + "].hardware.set";
      } else if (k == "baseline") {  // {"technique": "BASE-IS"}: the case the rows' speedups divide by
        if (!v.is_object() || v.empty()) throw at.error(in({k}), "expected an object of parameter values");
        for (const auto& [pk, pv] : v.items()) req.baseline[pk] = to_value(pv, at, in({k, pk}));
      } else {
        throw at.error(
            in({k}),
            "unknown key \"" + k + "\"; expected experiment, set, resolution, reps, warmup, quick, hardware, baseline");
      }
    }
    p.runs.push_back(std::move(req));
  }
  return p;
}

Preset load_preset(const std::string& dir, const std::string& name) {
  auto path = std::filesystem::path(dir) / (name + ".json");
  if (name.find('/') != std::string::npos || name.ends_with(".json")) path = name;
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) {
    std::string names;
    for (const auto& p : list_presets(dir)) names += (names.empty() ? "" : ", ") + p.name;
    throw UsageError("unknown preset '" + name + "'; presets in " + dir + ": " + (names.empty() ? "(none)" : names));
  }
  try {
    return parse_preset(path.stem().string(), path.string(), read_text_file(path.string(), "preset"));
  } catch (const FileError& e) {
    throw UsageError(e.what());
  }
}

std::vector<Preset> list_presets(const std::string& dir) {
  std::vector<Preset> out;
  std::error_code ec;
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec))
    if (e.path().extension() == ".json") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  for (const auto& f : files) {
    try {
      out.push_back(parse_preset(f.stem().string(), f.string(), read_text_file(f.string(), "preset")));
    } catch (const std::runtime_error& e) {  // UsageError, FileError
      out.push_back({f.stem().string(), std::string("(broken: ") + e.what() + ")", f.string(), {}});
    }
  }
  return out;
}

}  // namespace oitbench
