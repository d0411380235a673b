#pragma once
// Runs experiments: expands grids, interleaves the cases' repetitions, validates, writes rows.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/registry.hpp"

namespace oitbench {

inline constexpr int kCsvSchema = 1;

// One experiment to run, from the command line or from one entry of a preset.
struct RunRequest {
  std::string experiment;
  std::map<std::string, std::vector<std::string>> overrides;  // --set NAME=V1,V2
  std::optional<Resolution> resolution;
  std::optional<int> reps, warmup;
  bool quick = false;  // this request uses the experiment's --quick grid and resolution
};

struct RunOptions {
  ContextOptions context;
  std::optional<Resolution> resolution;  // overrides every request's and the experiments' defaults
  int reps = 5, warmup = 1;
  bool reps_given = false, warmup_given = false;
  bool quick = false;
  std::string out = "-";
  std::string raw;               // --raw: every repetition as a row
  std::string timer = "auto";    // auto | cpu | gpu
  bool interleave = true;
  std::string isolate = "auto";  // auto (hang-prone experiments) | always | never
  double timeout_s = 600;        // per case, watchdog
  bool progress = true;
  std::string preset_name;       // recorded in each row
  std::string shader_root;       // where shaders/ lives
  bool program_cache = true;     // reuse linked programs (glGetProgramBinary) across runs
};

// The CSV columns a run writes: fixed base columns, recorded environment, every registered
// experiment's metric columns and parameters (so files from any run of this schema concatenate).
std::vector<std::string> csv_columns(const Registry& registry);
std::vector<std::string> raw_columns(const Registry& registry);

// Validates the requests against the registry (throws UsageError listing the valid names).
void check_requests(const Registry& registry, const std::vector<RunRequest>& requests);

// Returns the process exit code: 0 finished, 1 errors or timeouts or interrupted (130), 3 nothing ran (unsupported).
int run_experiments(Registry& registry, const std::vector<RunRequest>& requests, const RunOptions& options);

// Exposed for tests and the CLI.
std::string default_shader_root();
const char* git_sha();  // generated at build time (cmake/version.cmake)

}  // namespace oitbench
