// oitbench list: the experiments with their parameters, the presets, the techniques, or the result schema.
#include <cstdio>

#include "app/commands.hpp"
#include "core/presets.hpp"
#include "core/schema.hpp"
#include "oit/techniques.hpp"

namespace oitbench::app {

namespace {

std::string size_text(const RunSize& s) {
  const std::string reps = !s.fixed_reps ? "reps until --target-ci, "
                           : s.reps == 1 ? "1 rep, "
                                         : std::to_string(s.reps) + " reps, ";
  return std::to_string(s.resolution.width) + "x" + std::to_string(s.resolution.height) + ", " + reps +
         std::to_string(s.warmup) + " warm-up";
}

// Which of a preset entry's sizes applies on this machine: a context tells whether the renderer is a
// software one (resolve_run_size); none may be available (no driver, no display), and then nobody knows.
enum class Here { Software, Hardware, Unknown };

Here describe_here(const ContextOptions& context) {
  try {
    auto ctx = create_context(context);
    auto gl = GlInfo::query();
    const bool software = gl.is_software_renderer();
    std::printf("Sizes here: %s renderer %s (%s): %s\n", software ? "software" : "hardware", gl.renderer.c_str(),
                ctx->backend().c_str(),
                software ? "every entry runs at its own size"
                         : "entries with a \"hardware\" size run at it, the others at their own");
    return software ? Here::Software : Here::Hardware;
  } catch (const ContextUnsupported& e) {
    std::printf("Sizes here: %s: cases would be unsupported here, rows would carry each entry's own size\n", e.what());
    return Here::Software;
  } catch (const std::exception& e) {
    std::printf("Sizes here: unknown: no GL context could be created (%s)\n", e.what());
    return Here::Unknown;
  }
}

void list_presets_command(const Registry& registry, const std::string& preset_dir, const ContextOptions& context) {
  std::printf(
      "Presets in %s (run with: oitbench run --preset NAME; --resolution, --reps and --warmup win over "
      "the sizes below):\n",
      preset_dir.c_str());
  const Here here = describe_here(context);
  RunOptions defaults;  // no --resolution, --reps or --warmup: the stopping rule decides, as in `run`
  defaults.sampling.adaptive = true;
  for (const auto& p : list_presets(preset_dir)) {
    std::printf("  %-18s %s\n", p.name.c_str(), p.description.c_str());
    for (const auto& r : p.runs) {
      std::printf("      %s", r.experiment.c_str());
      for (const auto& [k, v] : r.overrides) std::printf(" %s=%zu value(s)", k.c_str(), v.size());
      std::printf("\n");
      const Experiment* e = registry.find(r.experiment);
      if (!e) {
        std::printf("        (no experiment '%s' in this build)\n", r.experiment.c_str());
        continue;
      }
      auto mark = [&](Here which) { return here == which ? "   <- applies here" : ""; };
      std::printf("        software renderer: %s%s\n", size_text(resolve_run_size(r, *e, defaults, false)).c_str(),
                  mark(Here::Software));
      std::string hardware_set;
      if (r.hardware)
        for (const auto& [k, v] : r.hardware->set) {
          std::string values;
          for (const auto& x : v) values += (values.empty() ? "" : ",") + x;
          hardware_set += " " + k + "=" + values;
        }
      std::printf("        hardware:          %s%s%s%s\n", size_text(resolve_run_size(r, *e, defaults, true)).c_str(),
                  hardware_set.c_str(), r.hardware ? "" : " (no \"hardware\" entry: the same)", mark(Here::Hardware));
    }
  }
}

void list_techniques(bool json) {
  if (json) {
    std::fputs(oit::techniques_json().c_str(), stdout);
    return;
  }
  std::printf("Techniques of the oit experiment (run with: oitbench run oit --set technique=NAME,...):\n\n");
  std::printf("  %-11s %-12s %-6s %-7s %-20s %s\n", "name", "family", "scheme", "sort", "validated against",
              "parameters it reads");
  for (const auto& t : oit::techniques()) {
    std::string params;
    for (const auto& p : t.params) params += (params.empty() ? "" : " ") + p;
    std::printf("  %-11s %-12s %-6s %-7s %-20s %s%s\n", t.name.c_str(), oit::family_label(t.family).c_str(),
                oit::scheme_label(t.scheme).c_str(), t.sort.c_str(), oit::reference_label(t.reference()).c_str(),
                params.c_str(), t.in_quick ? "  (--quick)" : "");
  }
}

}  // namespace

int list_command(const Registry& registry, const ListOptions& o, const ContextOptions& context) {
  if (!o.schema.empty()) {
    if (o.schema != "json") throw UsageError("list --schema: unknown format '" + o.schema + "'; valid: json");
    std::fputs(schema_json(registry).c_str(), stdout);
    return 0;
  }
  if (o.json && !o.techniques) throw UsageError("list --json: only with --techniques (the schema: list --schema json)");
  if (o.techniques) {
    list_techniques(o.json);
    return 0;
  }
  if (o.presets) {
    list_presets_command(registry, o.preset_dir, context);
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
      if (!p.scope_text().empty()) std::printf("               applies where: %s\n", p.scope_text().c_str());
    }
    std::printf("\n");
  }
  return 0;
}

}  // namespace oitbench::app
