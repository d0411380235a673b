// oitbench render: one scene view with one OIT technique, its images and its CSV row.
#include <cstdio>
#include <filesystem>

#include "app/commands.hpp"
#include "core/presets.hpp"

namespace oitbench::app {

int render_command(Registry& registry, const RenderCommand& c) {
  std::string stem = c.out.ends_with(".png") ? c.out.substr(0, c.out.size() - 4) : c.out;
  RunRequest req{"oit",
                 {{"scene", {c.scene}}, {"view", {c.view}}, {"technique", {c.technique}}},
                 parse_resolution(c.resolution),
                 1,
                 0};
  for (const auto& s : c.sets) {
    auto [k, v] = parse_set_option(s);
    if (v.size() != 1) throw UsageError("render: --set " + k + " takes one value");
    req.overrides[k] = v;
  }
  RunOptions ropt = c.options;
  ropt.out = stem + ".csv";
  ropt.progress = false;
  ropt.image_stem = stem;
  int rc = run_experiments(registry, {req}, ropt);
  // Name only what is there: a case that failed wrote no image, an approximate one no depth view.
  std::string wrote;
  for (const char* suffix : {".png", ".pfm", "-diff8.png", "-depth.png", "-depth-histogram.csv", ".csv"})
    if (std::filesystem::exists(stem + suffix)) wrote += (wrote.empty() ? "" : ", ") + stem + suffix;
  if (!std::filesystem::exists(stem + ".png"))
    std::fprintf(stderr, "oitbench: no image written: the case did not finish (see its row in %s.csv)\n", stem.c_str());
  if (!wrote.empty()) std::fprintf(stderr, "oitbench: wrote %s\n", wrote.c_str());
  return rc;
}

}  // namespace oitbench::app
