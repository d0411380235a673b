#pragma once
// Presets: named grids kept as JSON files in presets/ (the grids that rerun a paper's table).
//   { "description": "...",
//     "runs": [ { "experiment": "occupancy", "set": { "variant": ["dynamic"], "size": [1, 2, 4] },
//                 "resolution": "800x600", "reps": 5, "warmup": 1 },
//               { "experiment": "sort", "quick": true } ] }   (quick: the experiment's --quick grid)
// An entry's sizes are for software renderers (llvmpipe); "hardware": {"resolution": "1920x1080", "reps": 10,
// "warmup": 2} gives those the runner uses instead on a hardware driver (resolve_run_size in runner.hpp).
#include <string>
#include <vector>

#include "core/runner.hpp"

namespace oitbench {

struct Preset {
  std::string name, description, path;
  std::vector<RunRequest> runs;
};

std::string default_preset_dir();
std::vector<Preset> list_presets(const std::string& dir);
// Throws UsageError naming the file, its line and column, the entry (runs[2].hardware.reps) and what was
// expected.
Preset load_preset(const std::string& dir, const std::string& name);
Preset parse_preset(const std::string& name, const std::string& path, const std::string& text);
inline constexpr int kMaxResolutionSide = 16384;
Resolution parse_resolution(const std::string& text);  // "800x600", each side in [1, 16384]; throws UsageError

}  // namespace oitbench
