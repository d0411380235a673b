// oitbench render: one scene view with one OIT technique, its images and its CSV row.
#include <cstdio>
#include <filesystem>
#include <map>

#include "app/commands.hpp"
#include "core/files.hpp"
#include "core/presets.hpp"

namespace oitbench::app {

namespace {

const char* const kSuffixes[] = {".png", ".pfm", "-diff8.png", "-depth.png", "-depth-histogram.csv", ".csv"};

// What a file was before the case ran: a file is named as written only if it is new or changed.
struct FileState {
  bool exists = false;
  std::filesystem::file_time_type mtime{};
  std::uintmax_t size = 0;
  bool operator==(const FileState&) const = default;
};
FileState state_of(const std::string& path) {
  std::error_code ec;
  FileState s;
  s.exists = std::filesystem::is_regular_file(path, ec);
  if (s.exists) {
    s.mtime = std::filesystem::last_write_time(path, ec);
    s.size = std::filesystem::file_size(path, ec);
  }
  return s;
}

}  // namespace

int render_command(Registry& registry, const RenderCommand& c) {
  // --out names a file: never a folder (whose files would become hidden ".png", ".csv"), never a device.
  const std::string name = std::filesystem::path(c.out).filename().string();
  if (c.out.empty() || c.out.back() == '/' || std::filesystem::is_directory(c.out) || name == ".png" || name.empty() ||
      name == "." || name == "..")
    throw UsageError(
        "--out " + c.out + ": names a folder; give an image file name, e.g. " +
        (c.out.empty() ? std::string("render.png") : (std::filesystem::path(c.out) / "render.png").string()));
  std::string stem = c.out.ends_with(".png") ? c.out.substr(0, c.out.size() - 4) : c.out;
  std::map<std::string, FileState> before;
  for (const char* suffix : kSuffixes) {
    check_output_file(stem + suffix, "--out");
    before[stem + suffix] = state_of(stem + suffix);
  }
  RunRequest req{"oit",
                 {{"scene", {c.scene}}, {"view", {c.view}}, {"technique", {c.technique}}},
                 parse_resolution(c.resolution),
                 1,
                 0};
  for (const auto& [k, v] : parse_set_options(c.sets)) {
    if (v.size() != 1) throw UsageError("render: --set " + k + " takes one value");
    if (req.overrides.count(k)) throw UsageError("render: give the " + k + " as --" + k + ", not as --set " + k);
    req.overrides[k] = v;
  }
  RunOptions ropt = c.options;
  ropt.out = stem + ".csv";
  ropt.progress = false;
  ropt.image_stem = stem;
  int rc = run_experiments(registry, {req}, ropt);
  // Name only what this run wrote: a case that failed wrote no image, an approximate one no depth view,
  // and a file left by an earlier render is not this one's.
  std::string wrote;
  for (const char* suffix : kSuffixes)
    if (auto now = state_of(stem + suffix); now.exists && !(now == before[stem + suffix]))
      wrote += (wrote.empty() ? "" : ", ") + stem + suffix;
  if (auto png = state_of(stem + ".png"); !png.exists || png == before[stem + ".png"])
    std::fprintf(stderr, "oitbench: no image written: the case did not finish (see its row in %s.csv)\n", stem.c_str());
  if (!wrote.empty()) std::fprintf(stderr, "oitbench: wrote %s\n", wrote.c_str());
  return rc;
}

}  // namespace oitbench::app
