#pragma once
// `oitbench view`: one scene rendered live in a GLFW window by the oit experiment's own cases
// (micro/oit/oit_case.hpp), with a fly camera, keys to switch technique, BMA, MAX_FRAGS and
// capture storage, per-pass timings and depth complexity on screen, and a key that saves the
// camera as a named view into the scene file. `--frames`, `--keys` and `--screenshot` let tests
// drive it under xvfb-run.
#include <optional>
#include <string>
#include <vector>

#include "backends/backend.hpp"
#include "core/registry.hpp"
#include "oit/techniques.hpp"

namespace oitbench::viewer {

struct ViewerOptions {
  std::string scene = "planes";  // name in scenes/ or a path to a .json
  std::string view;              // empty: the scene file's first view
  std::string technique = oit::default_technique();
  std::string size = "800x600";   // window WIDTHxHEIGHT
  std::string detail = "full";    // full | small
  std::vector<std::string> sets;  // other oit parameters, NAME=VALUE
  int frames = 0;                 // > 0: render this many frames, then exit
  std::string screenshot;         // PNG of the last frame (and of P presses)
  std::string keys;               // scripted presses, "2:T,4:Z,6:V"
  std::string save_view;          // name for V (default view-1, view-2, ...)
  std::string shader_root;        // empty: the default shaders/
  bool gl_debug = false;
  std::optional<unsigned long long> memory_limit;  // --memory-limit: replaces the CPU limit (core/memory_budget.hpp)
};

// The key table (for --help and the README).
std::string key_help();

// Opens the window and runs until Esc, the window closes, or `frames` frames. Returns the exit code:
// 0, or 1 when a case could not be built or a view/screenshot not saved along the way. Throws
// UsageError for bad options (listing the valid values) and BackendError without a display.
int run_viewer(Registry& registry, const ViewerOptions& options);

}  // namespace oitbench::viewer
