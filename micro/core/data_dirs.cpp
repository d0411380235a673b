#include "core/data_dirs.hpp"

#include <cstdlib>
#include <filesystem>
#include <stdexcept>

namespace oitbench {

namespace {

struct Kind {
  const char* name;
  const char* env;
  const char* marker;  // a file every copy of the folder has, so an unrelated folder of that name is skipped
};

constexpr Kind kKinds[] = {{"shaders", "OITBENCH_SHADERS", "common/oitbench.glsl"},
                           {"scenes", "OITBENCH_SCENES", "planes.json"},
                           {"presets", "OITBENCH_PRESETS", "default.json"}};

}  // namespace

DataDirLookup find_data_dir(const std::string& kind) {
  const Kind* k = nullptr;
  for (const auto& c : kKinds)
    if (kind == c.name) k = &c;
  if (!k) throw std::invalid_argument("data_dir: unknown kind '" + kind + "' (shaders, scenes, presets)");
  if (const char* env = std::getenv(k->env); env && *env) return {env, std::string("$") + k->env};
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec)
    for (fs::path dir = exe.parent_path(); !dir.empty(); dir = dir.parent_path()) {
      for (const fs::path& candidate : {dir / k->name, dir / "share" / "oitbench" / k->name})
        if (fs::exists(candidate / k->marker, ec)) return {candidate.string(), "walking up from the binary"};
      if (dir == dir.root_path()) break;
    }
  return {(fs::path(OITBENCH_SOURCE_DIR) / k->name).string(), "the source tree"};
}

std::string data_dir(const std::string& kind) { return find_data_dir(kind).path; }

}  // namespace oitbench
