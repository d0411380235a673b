// oitbench run: experiments by name (or `all`) or a preset, with --set overrides, into CSV.
#include "app/commands.hpp"
#include "core/presets.hpp"

namespace oitbench::app {

int run_command(Registry& registry, RunCommand& c) {
  RunOptions& ropt = c.options;
  if (!c.resolution.empty()) ropt.resolution = parse_resolution(c.resolution);
  const auto overrides = parse_set_options(c.sets);
  std::vector<RunRequest> requests;
  if (!c.preset.empty()) {
    if (!c.experiments.empty()) throw UsageError("give either --preset or experiment names, not both");
    auto p = load_preset(c.preset_dir, c.preset);
    if (ropt.preset_name.empty()) ropt.preset_name = p.name;
    requests = p.runs;
    for (auto& r : requests)
      for (const auto& [k, v] : overrides) r.overrides[k] = v;
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
  return run_experiments(registry, requests, ropt);
}

}  // namespace oitbench::app
