#pragma once
// The subcommands of `oitbench`, one function each; app/cli.cpp parses the command line into their
// options and maps what they throw to exit codes (2 usage, 3 no context, 1 anything else).
#include <string>
#include <vector>

#include "core/runner.hpp"
#include "oit/techniques.hpp"

namespace oitbench::app {

struct ListOptions {
  bool presets = false;
  std::string schema;       // "json": print the result schema instead
  bool techniques = false;  // print the oit experiment's technique table instead
  bool json = false;        // ... as JSON (scripts/techniques.json)
  std::string preset_dir;
};
// `list --presets` creates a context with `context` to say which of each entry's sizes applies here.
int list_command(const Registry& registry, const ListOptions& o, const ContextOptions& context);

int info_command(const ContextOptions& o);
// info --drivers: every driver of backends/drivers.hpp and EGL device, tried in a child process each.
int drivers_command(const ContextOptions& o);

struct RunCommand {
  RunOptions options;
  std::vector<std::string> experiments, sets;
  std::string preset, resolution, preset_dir;
  std::vector<std::string> baseline;  // --baseline NAME=VALUE: the speedups' baseline
  std::vector<std::string> tags;      // --tag KEY=VALUE
};
int run_command(Registry& registry, RunCommand& c);

struct RenderCommand {
  RunOptions options;
  std::string scene = "planes", view = "fwd", technique = oit::default_technique(), out = "render.png",
              resolution = "512x512";
  std::vector<std::string> sets;
};
int render_command(Registry& registry, const RenderCommand& c);

}  // namespace oitbench::app
