// oitbench run: experiments by name (or `all`) or a preset, with --set overrides, into CSV.
#include <algorithm>

#include "app/commands.hpp"
#include "core/presets.hpp"
#include "core/provenance.hpp"

namespace oitbench::app {

int run_command(Registry& registry, RunCommand& c) {
  RunOptions& ropt = c.options;
  if (!c.resolution.empty()) try {
      ropt.resolution = parse_resolution(c.resolution);
    } catch (const UsageError& e) {
      throw UsageError(std::string("--resolution: ") + e.what());
    }
  ropt.tags = parse_tags(c.tags);
  if (!ropt.run_id.empty() && !is_run_id(ropt.run_id))
    throw UsageError("--run-id " + ropt.run_id + ": give a UUID like 0f8fad5b-d9cb-469f-a165-70867728950e");
  const auto overrides = parse_set_options(c.sets);
  std::vector<RunRequest> requests;
  if (!c.preset.empty()) {
    if (!c.experiments.empty()) throw UsageError("give either --preset or experiment names, not both");
    Preset p;
    try {
      p = load_preset(c.preset_dir, c.preset);
    } catch (const UsageError& e) {
      throw UsageError("--preset " + c.preset + ": " + e.what());
    }
    if (ropt.preset_name.empty()) ropt.preset_name = p.name;
    requests = p.runs;
    for (auto& r : requests)
      for (const auto& [k, v] : overrides) {
        r.overrides[k] = v;
        if (r.hardware) r.hardware->set.erase(k);  // the command line decides on every driver
      }
  } else {
    if (c.experiments.empty())
      throw UsageError("run: name an experiment, 'all' or --preset NAME; experiments: " + registry.names());
    for (const auto& n : c.experiments) {
      if (n == "all") {
        for (const auto& e : registry.all()) requests.push_back({e->name(), {}, {}, {}, {}});
      } else {
        requests.push_back({n, {}, {}, {}, {}});
      }
    }
    // With several experiments a --set applies where the parameter exists; it must exist somewhere.
    for (const auto& [k, v] : overrides) {
      bool used = false;
      for (auto& r : requests) {
        const auto* e = registry.find(r.experiment);
        if (!e) continue;
        for (const auto& p : registry.params_of(*e))
          if (p.name == k) {
            r.overrides[k] = v;
            used = true;
          }
      }
      if (!used && requests.size() > 1)
        throw UsageError("no selected experiment has a parameter '" + k + "' (see: oitbench list)");
      if (!used) requests[0].overrides[k] = v;  // check_requests names the valid parameters
    }
  }
  // --baseline NAME=VALUE ...: every request whose experiment has those parameters divides by that case
  // (replacing a preset's own baseline); one that no request can take is a usage error.
  if (!c.baseline.empty()) {
    std::map<std::string, std::string> baseline;
    for (const auto& b : c.baseline) {
      std::pair<std::string, std::vector<std::string>> kv;
      try {
        kv = parse_set_option(b);
      } catch (const UsageError&) {
        throw UsageError("--baseline " + b + ": expected NAME=VALUE, e.g. technique=" + oit::default_technique());
      }
      const auto& [k, v] = kv;
      if (v.size() != 1) throw UsageError("--baseline " + b + ": give one value, NAME=VALUE");
      if (baseline.count(k))
        throw UsageError("--baseline " + k + " is given twice (" + k + "=" + baseline[k] + " and " + b +
                         "); a baseline is one case: give each parameter once");
      baseline[k] = v[0];
    }
    bool taken = false;
    for (auto& r : requests) {
      const auto* e = registry.find(r.experiment);
      if (!e) continue;
      auto specs = registry.params_of(*e);
      bool has_all = std::all_of(baseline.begin(), baseline.end(), [&](const auto& kv) {
        return std::any_of(specs.begin(), specs.end(), [&](const ParamSpec& s) { return s.name == kv.first; });
      });
      if (has_all || requests.size() == 1) {
        r.baseline = baseline;
        taken = true;
      }
    }
    if (!taken) throw UsageError("no selected experiment has the parameters of --baseline (see: oitbench list)");
    try {
      check_requests(registry, requests, ropt.quick, ropt.max_cases);
    } catch (const UsageError& e) {  // the baseline's value or a baseline outside the grid
      if (std::string(e.what()).find("the baseline ") == std::string::npos) throw;
      throw UsageError(std::string("--baseline: ") + e.what());
    }
  }
  return run_experiments(registry, requests, ropt);
}

}  // namespace oitbench::app
