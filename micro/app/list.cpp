// oitbench list: the experiments with their parameters, the presets, or the result schema.
#include <cstdio>

#include "app/commands.hpp"
#include "core/presets.hpp"
#include "core/schema.hpp"

namespace oitbench::app {

int list_command(const Registry& registry, const ListOptions& o) {
  if (!o.schema.empty()) {
    if (o.schema != "json") throw UsageError("list --schema: unknown format '" + o.schema + "'; valid: json");
    std::fputs(schema_json(registry).c_str(), stdout);
    return 0;
  }
  const std::string& preset_dir = o.preset_dir;
  if (o.presets) {
    std::printf("Presets in %s (run with: oitbench run --preset NAME):\n", preset_dir.c_str());
    for (const auto& p : list_presets(preset_dir)) {
      std::printf("  %-18s %s\n", p.name.c_str(), p.description.c_str());
      for (const auto& r : p.runs) {
        std::printf("      %s", r.experiment.c_str());
        for (const auto& [k, v] : r.overrides) std::printf(" %s=%zu value(s)", k.c_str(), v.size());
        std::printf("\n");
      }
    }
    return 0;
  }
  std::printf("Experiments (run with: oitbench run NAME [--set PARAM=V1,V2,...]):\n\n");
  for (const auto& e : registry.all()) {
    auto dr = e->default_resolution();
    auto qr = e->quick_resolution();
    std::printf("%s\n  %s\n  resolution %dx%d (--quick %dx%d)%s\n", e->name().c_str(), e->description().c_str(),
                dr.width, dr.height, qr.width, qr.height, e->hang_prone() ? ", hang-prone: cases run isolated" : "");
    for (const auto& p : registry.params_of(*e)) {
      auto join = [](const std::vector<std::string>& v) {
        std::string s;
        for (const auto& x : v) s += (s.empty() ? "" : ",") + x;
        return s;
      };
      std::printf("    %-10s %s\n               default: %s%s\n               allowed: %s\n", p.name.c_str(),
                  p.description.c_str(), join(p.defaults).c_str(),
                  p.quick.empty() ? "" : ("  (--quick: " + join(p.quick) + ")").c_str(), p.allowed_text().c_str());
      if (!p.applies_when.empty()) std::printf("               applies where: %s\n", p.scope_text().c_str());
    }
    std::printf("\n");
  }
  return 0;
}

}  // namespace oitbench::app
