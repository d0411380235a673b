#include "core/presets.hpp"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>

#include "core/data_dirs.hpp"
#include "core/text_position.hpp"

namespace oitbench {

namespace {

std::string to_value(const nlohmann::json& v, const std::string& where) {
  if (v.is_string()) return v.get<std::string>();
  if (v.is_number_integer()) return std::to_string(v.get<long long>());
  if (v.is_number()) {
    std::ostringstream s;
    s << v.get<double>();
    return s.str();
  }
  if (v.is_boolean()) return v.get<bool>() ? "1" : "0";
  throw UsageError(where + ": expected a string or a number, got " + std::string(v.type_name()));
}
}  // namespace

Resolution parse_resolution(const std::string& text) {
  static const std::regex re(R"((\d{1,5})x(\d{1,5}))");
  std::smatch m;
  if (!std::regex_match(text, m, re))
    throw UsageError("resolution '" + text + "': expected WIDTHxHEIGHT, e.g. 800x600");
  Resolution r{std::stoi(m[1]), std::stoi(m[2])};
  if (r.width < 1 || r.height < 1 || r.width > 16384 || r.height > 16384)
    throw UsageError("resolution '" + text + "': each side must be in [1, 16384]");
  return r;
}

std::string default_preset_dir() { return data_dir("presets"); }

Preset parse_preset(const std::string& name, const std::string& path, const std::string& text) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw UsageError(path + ":" + line_column(text, e.byte > 0 ? e.byte - 1 : 0) + ": malformed JSON: " + e.what());
  }
  // nlohmann does not keep positions of values: name the JSON path of what is wrong instead.
  Preset p{name, "", path, {}};
  if (!j.is_object()) throw UsageError(path + ": expected a JSON object at the top level");
  if (j.contains("description")) p.description = j["description"].get<std::string>();
  if (!j.contains("runs") || !j["runs"].is_array() || j["runs"].empty())
    throw UsageError(path + ": expected \"runs\": a non-empty array of {\"experiment\": ..., \"set\": {...}}");
  for (size_t i = 0; i < j["runs"].size(); ++i) {
    const auto& r = j["runs"][i];
    std::string where = path + ": runs[" + std::to_string(i) + "]";
    if (!r.is_object() || !r.contains("experiment") || !r["experiment"].is_string())
      throw UsageError(where + ": expected an object with \"experiment\": \"NAME\"");
    RunRequest req;
    req.experiment = r["experiment"].get<std::string>();
    for (const auto& [k, v] : r.items()) {
      if (k == "experiment") continue;
      if (k == "set") {
        if (!v.is_object()) throw UsageError(where + ".set: expected an object of parameter lists");
        for (const auto& [pk, pv] : v.items()) {
          auto& list = req.overrides[pk];
          if (pv.is_array()) {
            for (const auto& x : pv) list.push_back(to_value(x, where + ".set." + pk));
          } else {
            list.push_back(to_value(pv, where + ".set." + pk));
          }
          if (list.empty()) throw UsageError(where + ".set." + pk + ": empty value list");
        }
      } else if (k == "resolution") {
        req.resolution = parse_resolution(to_value(v, where + ".resolution"));
      } else if (k == "reps" || k == "warmup") {
        if (!v.is_number_integer() || v.get<int>() < (k == "reps" ? 1 : 0))
          throw UsageError(where + "." + k + ": expected a " + (k == "reps" ? "positive" : "non-negative") +
                           " integer");
        (k == "reps" ? req.reps : req.warmup) = v.get<int>();
      } else if (k == "quick") {
        if (!v.is_boolean()) throw UsageError(where + ".quick: expected true or false");
        req.quick = v.get<bool>();
      } else {
        throw UsageError(where + ": unknown key \"" + k +
                         "\"; expected experiment, set, resolution, reps, warmup, quick");
      }
    }
    p.runs.push_back(std::move(req));
  }
  return p;
}

Preset load_preset(const std::string& dir, const std::string& name) {
  auto path = std::filesystem::path(dir) / (name + ".json");
  if (name.find('/') != std::string::npos || name.ends_with(".json")) path = name;
  std::ifstream in(path);
  if (!in) {
    std::string names;
    for (const auto& p : list_presets(dir)) names += (names.empty() ? "" : ", ") + p.name;
    throw UsageError("unknown preset '" + name + "'; presets in " + dir + ": " + (names.empty() ? "(none)" : names));
  }
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_preset(path.stem().string(), path.string(), ss.str());
}

std::vector<Preset> list_presets(const std::string& dir) {
  std::vector<Preset> out;
  std::error_code ec;
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec))
    if (e.path().extension() == ".json") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  for (const auto& f : files) {
    std::ifstream in(f);
    std::stringstream ss;
    ss << in.rdbuf();
    try {
      out.push_back(parse_preset(f.stem().string(), f.string(), ss.str()));
    } catch (const UsageError& e) {
      out.push_back({f.stem().string(), std::string("(broken: ") + e.what() + ")", f.string(), {}});
    }
  }
  return out;
}

}  // namespace oitbench
