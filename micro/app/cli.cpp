#include "app/cli.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <stdexcept>

#include "app/commands.hpp"
#include "app/number_option.hpp"
#include "backends/drivers.hpp"
#include "core/csv.hpp"
#include "core/files.hpp"
#include "core/memory_budget.hpp"
#include "core/outcomes.hpp"
#include "core/presets.hpp"
#include "core/provenance.hpp"
#include "core/runner.hpp"
#include "experiments/experiments.hpp"
#include "viewer/viewer.hpp"

namespace oitbench {

using namespace app;

namespace {

// Every subcommand's options, filled by CLI11, read by the subcommand's execute function.
struct CliState {
  Registry registry;
  ContextOptions context;
  std::string driver = "default";
  std::string device;  // --device as given; resolved into context.device by apply_context
  ListOptions list;
  bool info_drivers = false;
  RunCommand run;
  double target_ci_pct = 0;
  double warmup_settle_pct = 0;
  bool no_interleave = false, no_progress = false, no_program_cache = false, no_mem_probe = false;
  std::string shard;              // --shard I/N or auto
  std::string memory_limit;       // --memory-limit SIZE as given
  std::string view_memory_limit;  // view's
  RenderCommand render;
  viewer::ViewerOptions view;
};

// A subcommand: its name and help, the options it declares and what it does once they are parsed.
struct Subcommand {
  const char* name;
  const char* help;
  void (*declare)(CLI::App&, CliState&);
  int (*execute)(const CLI::App&, CliState&);
};

// `oitbench --version` and `oitbench version`: the version, then the build options.
std::string version_text() {
  std::string s = std::string("oitbench ") + version_string() + "\n" + build_options();
  while (!s.empty() && s.back() == '\n') s.pop_back();
  return s;
}

// The one check of every numeric option (app/number_option.hpp): nan, inf, text and values out of
// bounds are refused with the bounds written readably; CLI11 prefixes the option's name.
CLI::Validator number(NumberBounds b) {
  return CLI::Validator([b](std::string& text) { return check_number(text, b); }, describe(b));
}
NumberBounds whole(double lo, double hi) { return {lo, hi, false, false, true, ""}; }

constexpr double kWeekSeconds = 604800;

constexpr const char* kExitCodes =
    "Exit codes: 0 done (rows may still be invalid: see the status column), 1 errors or timeouts,\n"
    "2 usage error, 3 nothing could run on this driver (all unsupported), 4 an outcome --expect did not\n"
    "expect (with --expect: 0 when every outcome was expected), 130 interrupted.";

// --device N|cuda:N|drm:PATH|auto into the EGL device index (backends/device_select.hpp); exit 2 listing
// the devices when it names none. Anything but a plain index says on stderr how it chose.
// --memory-limit's SIZE (run and view): what parse_byte_size accepts, its message where it does not.
CLI::Validator byte_size_validator() {
  return CLI::Validator(
      [](std::string& text) {
        try {
          parse_byte_size(text);
          return std::string();
        } catch (const std::invalid_argument& e) {
          return std::string(e.what());
        }
      },
      "SIZE");
}

void resolve_device(CliState& s) {
  std::vector<DeviceDescription> devices;
  for (const auto& d : list_egl_devices()) devices.push_back(d);
  DeviceChoice c = choose_device(s.device, devices, device_environment());
  if (!c.error.empty())
    throw UsageError("--device " + s.device + ": " + c.error +
                     (c.rule.rfind("auto", 0) == 0 ? " [" + c.rule + "]" : "") +
                     "; devices found: " + describe_devices(devices));
  s.context.device = c.index;
  if (c.rule != "index " + s.device)
    std::fprintf(stderr, "oitbench: --device %s -> EGL device %d (%s)\n", s.device.c_str(), c.index, c.rule.c_str());
}

// --driver and --device into the context options (a usage error when they do not fit together).
void apply_context(CliState& s) {
  try {
    apply_driver(find_driver(s.driver), s.context);
  } catch (const BackendError& e) {
    throw UsageError(std::string("--driver: ") + e.what());
  }
  if (s.device.empty()) return;
  if (s.context.backend != "egl-device") {
    if (s.device == "0") return;
    throw UsageError("--device " + s.device + " applies to --backend egl-device only (this is --backend " +
                     s.context.backend + "); see: oitbench info --drivers");
  }
  resolve_device(s);
}

void add_backend(CLI::App& cmd, CliState& s) {
  cmd.add_option("--backend", s.context.backend,
                 "Context backend: egl (surfaceless, default), egl-device, osmesa, glfw")
      ->check(CLI::IsMember(compiled_backends()));
  cmd.add_option("--device", s.device,
                 "EGL device for --backend egl-device: N (index), cuda:N, drm:/dev/dri/renderD128, auto "
                 "(CUDA_VISIBLE_DEVICES / Slurm's GPUs; see docs/ci.md); list: oitbench info --backend egl-device")
      ->check(CLI::Validator(
          [](std::string& v) {
            std::string e = choose_device(v, {}, {}).error;
            bool syntax = e.rfind("unknown device", 0) == 0 || e.rfind("cuda:", 0) == 0 || e.rfind("drm:", 0) == 0;
            return syntax ? e : std::string();
          },
          "N|cuda:N|drm:PATH|auto", "device"));
  cmd.add_flag("--gl-debug", s.context.debug, "Print KHR_debug messages to stderr");
  cmd.add_option("--driver", s.driver,
                 "GL driver: default (what the loader gives), llvmpipe, zink (GL on Vulkan on lavapipe), softpipe, "
                 "egl-device-N; see: oitbench info --drivers");
}

void declare_list(CLI::App& list, CliState& s) {
  s.list.preset_dir = default_preset_dir();
  list.add_flag("--presets", s.list.presets, "List the presets (named grids in presets/*.json)");
  list.add_option("--schema", s.list.schema,
                  "Print the CSV schema (columns with role, type, unit and meaning; statuses) as FORMAT: json");
  list.add_flag("--techniques", s.list.techniques,
                "List the oit experiment's techniques (family, resolve scheme and sort, parameters read, reference)");
  list.add_flag("--json", s.list.json,
                "With --techniques: print the table as JSON (what scripts/techniques.json holds)");
  list.add_option("--presets-dir", s.list.preset_dir, "Preset directory (default: the source tree's presets/)");
  add_backend(list, s);  // list --presets creates a context to say which size applies here
}

int execute_list(const CLI::App&, CliState& s) {
  if (s.list.presets) apply_context(s);
  return list_command(s.registry, s.list, s.context);
}

void declare_info(CLI::App& info, CliState& s) {
  add_backend(info, s);
  info.add_flag("--drivers", s.info_drivers,
                "List the GL drivers this machine offers (each tried in a child process): name, renderer, version, "
                "whether oitbench can run on it");
}

int execute_info(const CLI::App&, CliState& s) {
  if (s.info_drivers) return drivers_command(s.context);
  apply_context(s);
  return info_command(s.context);
}

// run's options that size the samples and stop them (docs/measurement.md#samples-sized-by-their-statistics).
void declare_sampling(CLI::App& run, CliState& s) {
  RunOptions& o = s.run.options;
  s.target_ci_pct = o.sampling.target_ci * 100;
  s.warmup_settle_pct = o.sampling.warmup_settle * 100;
  o.sampling.max_case_s = 10;  // a 2-core machine's reference runs: 10 timed seconds per case at most
  const char* sizing = "Samples and stopping";
  run.add_option("--target-ci", s.target_ci_pct,
                 "Repeat until the 95% interval of each case's median is within +-this % (default 3); --reps N "
                 "fixes the count instead")
      ->check(number({0, 1000, true, false, false, "%"}))
      ->group(sizing);
  run.add_option("--max-reps", o.sampling.max_reps, "At most this many timed repetitions per case (default 30)")
      ->transform(number(whole(2, 100000)))
      ->group(sizing);
  run.add_option("--max-case-s", o.sampling.max_case_s,
                 "At most this many timed seconds per case (a group of n cases: n times it; default 10)")
      ->check(number({0, kWeekSeconds, true, false, false, "seconds"}))
      ->group(sizing);
  run.add_option("--min-sample-ms", o.sampling.min_sample_ms,
                 "A sample runs the case's repetition often enough to last this long (default 20; 0: once)")
      ->check(number({0, 60000, false, false, false, "ms"}))
      ->group(sizing);
  run.add_option("--warmup-settle", s.warmup_settle_pct,
                 "The last warm-up repetition counts as the first sample where the first timed one shows it had "
                 "settled: at most this % slower than it (default 10; 0: never)")
      ->check(number({0, 1e6, false, false, false, "%"}))
      ->group(sizing);
  run.add_option("--max-sample-ms", o.sampling.max_sample_ms,
                 "A repetition longer than this runs fewer units of scalable work (occupancy's draws), times "
                 "scaled back (default 500; 0: never)")
      ->check(number({0, 3600000, false, false, false, "ms"}))
      ->group(sizing);
  run.add_option("--baseline", s.run.baseline,
                 "NAME=VALUE ...: the case each speedup divides by, run in every interleaved group of the cases "
                 "it is the baseline of (e.g. technique=" +
                     oit::default_technique() + "); replaces a preset's")
      ->take_all()
      ->group(sizing);
}

// run's options that choose the cases and where their rows go.
void declare_run_grid(CLI::App& run, CliState& s) {
  RunOptions& o = s.run.options;
  run.add_option("experiments", s.run.experiments, "Experiment names, or 'all' (see: oitbench list)");
  run.add_option("--set", s.run.sets,
                 "NAME=V1,V2,... (integer ranges A..B or A..B:STEP); repeatable. A parameter "
                 "scoped to some techniques or variants must apply to at least one selected case")
      ->take_all();
  run.add_option("--preset", s.run.preset, "Run a named grid from presets/ (see: oitbench list --presets)");
  run.add_option("--resolution", s.run.resolution, "Render target WIDTHxHEIGHT (default: each experiment's own)");
  run.add_option("--reps", o.reps,
                 "Timed repetitions per case: a fixed count (default: until --target-ci is reached; --quick 3)")
      ->transform(number(whole(1, 100000)));
  run.add_option("--warmup", o.warmup, "Untimed repetitions first (default 1)")->transform(number(whole(0, 1000)));
  run.add_flag("--quick", o.quick, "Each experiment's small grid and resolution: finishes in seconds");
  run.add_option("--out,-o", o.out, "CSV file (appends when the header matches; '-' = stdout)");
  run.add_option("--raw", o.raw, "Also write every repetition (one row per sample) to this CSV");
  run.add_option("--max-cases", o.max_cases,
                 "The most cases one run may have (default 100000), checked before anything is built")
      ->transform(number(whole(1, 100000000)));
  run.add_flag("--dry-run", o.dry_run,
               "Print the plan on this driver (each request's experiment, resolution, cases, reps, warm-up) and "
               "run nothing: no CSV is written");
  run.add_option("--preset-name", o.preset_name, "Recorded in the preset column")->group("");
  run.add_option("--run-id", o.run_id, "The run's UUID (set by the parent for an isolated case)")->group("");
  run.add_flag("--isolated-child", o.isolated_child, "Set by the parent for an isolated case")->group("");
}

// run's options that say how the cases are executed.
void declare_run_execution(CLI::App& run, CliState& s) {
  RunOptions& o = s.run.options;
  run.add_option("--timer", o.timer, "Primary clock: auto (CPU on software renderers, GPU queries elsewhere), cpu, gpu")
      ->check(CLI::IsMember({"auto", "cpu", "gpu"}));
  run.add_flag("--sync-passes", o.sync_passes,
               "glFinish around every timed pass on hardware drivers too (serialises the pipeline; software "
               "renderers always do it). Default there: passes back to back, timed by GL_TIME_ELAPSED queries");
  run.add_flag("--no-program-cache", s.no_program_cache,
               "Compile every program from source (to measure compile time); default: reuse linked programs "
               "from ~/.cache/oitbench/programs (glGetProgramBinary, keyed on sources, defines and driver)");
  run.add_flag("--no-mem-probe", s.no_mem_probe,
               "Do not measure the host's memory latency after each timed round (about 1 ms a round; the "
               "host_mem_ns columns stay empty). On a software renderer it tells a slow list traversal from a "
               "slow host: docs/drivers.md");
  run.add_option("--mem-probe-mib", o.mem_probe_mib,
                 "The memory probe's buffer in MiB (default 64): larger than the CPU's last-level cache (AMD's "
                 "3D V-Cache has 96 MiB and more), or the chase measures the cache")
      ->transform(number(whole(1, 4096)));
  run.add_flag("--no-interleave", s.no_interleave,
               "Run each case's repetitions back to back (default: A B C A B C ...)");
  run.add_option("--isolate", o.isolate,
                 "Run cases in child processes under the watchdog: auto (hang-prone experiments), always, never")
      ->check(CLI::IsMember({"auto", "always", "never"}));
  run.add_option("--memory-limit", s.memory_limit,
                 "The most memory one case may hold: CPU memory, and on a software renderer its GPU buffers too "
                 "(SIZE: 8G, 512M, ...; default: MemAvailable and this process's RLIMIT_AS/RLIMIT_DATA). A case "
                 "whose estimate is larger is unsupported, decided before it allocates")
      ->check(byte_size_validator());
  run.add_option("--timeout", o.timeout_s, "Watchdog: seconds a case may take before it is killed (status timeout)")
      ->check(number({0, kWeekSeconds, true, false, false, "seconds"}));
  run.add_flag("--no-progress", s.no_progress, "No progress line on stderr");
  run.add_option("--shaders", o.shader_root,
                 "Shader directory (default: shaders/ found from the binary, else the source tree's; see: oitbench "
                 "info)");
  run.add_option("--presets-dir", s.run.preset_dir,
                 "Preset directory (default: presets/ found from the binary, else the source tree's)");
}

// run's options for fleets and CI (docs/ci.md).
void declare_fleet(CLI::App& run, CliState& s) {
  const char* fleet = "Fleets and CI (docs/ci.md)";
  run.add_option("--shard", s.shard,
                 "I/N: run the I-th of N disjoint parts of the grid (1 <= I <= N; together the whole grid, an "
                 "interleaved group and its baseline never split); auto: I and N from a Slurm array, a Kubernetes "
                 "Indexed Job or GitLab's parallel:")
      ->group(fleet);
  run.add_option("--expect", s.run.options.expect,
                 "Expected-status baseline: lines PATTERN STATUS (a case key or glob; invalid, unsupported, error, "
                 "timeout, flaky). Exit 0 when every outcome is expected, 4 when one is not (a new failure, or a "
                 "listed one that now passes); writes this run's list to OUT.expect (or --write-expect)")
      ->group(fleet);
  run.add_option("--write-expect", s.run.options.write_expect,
                 "Write the baseline this run would expect (every case not ok with its status) to this file")
      ->group(fleet);
  run.add_option("--junit", s.run.options.junit,
                 "Also write a JUnit XML report: one testcase per case (time: its median), properties driver, "
                 "renderer, commit")
      ->group(fleet);
  run.add_option("--tag", s.run.tags,
                 "KEY=VALUE, repeatable: a label every row carries in its tags column (a driver's commit, a machine "
                 "pool, a CI job's address); keys start with a letter, A-Z a-z 0-9 _ . -")
      ->take_all()
      ->group(fleet);
}

void declare_run(CLI::App& run, CliState& s) {
  run.footer(std::string("The CSV gets one row per case and pass (see README, 'CSV schema'). Rows are written as each "
                         "case\n(or interleaved group) finishes: Ctrl-C leaves every finished row.\n") +
             kExitCodes);
  add_backend(run, s);
  s.run.preset_dir = default_preset_dir();
  s.run.options.shader_root = default_shader_root();
  declare_run_grid(run, s);
  declare_run_execution(run, s);
  declare_sampling(run, s);
  declare_fleet(run, s);
}

// --out and --raw: files (or new names), never the same one twice.
void check_outputs(const RunOptions& o) {
  check_output_file(o.out, "--out");
  if (o.raw.empty()) return;
  check_output_file(o.raw, "--raw");
  if (o.raw == o.out || (o.out != "-" && std::filesystem::exists(o.out) && std::filesystem::exists(o.raw) &&
                         std::filesystem::equivalent(o.out, o.raw)))
    throw UsageError("--raw and --out name the same file (" + o.raw + "); give two files");
}

// --junit and the expected-status list a run writes: files (or new names) like --out.
void check_fleet_outputs(const RunOptions& o) {
  if (!o.junit.empty()) check_output_file(o.junit, "--junit");
  if (const auto path = write_expect_path(o); !path.empty())
    check_output_file(path, o.write_expect.empty() ? "--expect (its list, written beside --out)" : "--write-expect");
}

int execute_run(const CLI::App& run, CliState& s) {
  apply_context(s);
  RunOptions& o = s.run.options;
  o.context = s.context;
  check_outputs(o);
  check_fleet_outputs(o);
  o.reps_given = run.count("--reps") > 0;
  o.sampling.adaptive = true;  // unless --reps, a preset entry's reps or --quick fix the count
  o.sampling.target_ci = s.target_ci_pct / 100;
  o.sampling.warmup_settle = s.warmup_settle_pct / 100;
  o.warmup_given = run.count("--warmup") > 0;
  o.interleave = !s.no_interleave;
  o.mem_probe = !s.no_mem_probe;
  o.program_cache = !s.no_program_cache;
  o.progress = !s.no_progress;
  if (!s.memory_limit.empty()) o.memory_limit = parse_byte_size(s.memory_limit);
  if (!s.shard.empty()) {
    o.shard = parse_shard(s.shard);
    if (!o.shard.source.empty())
      std::fprintf(stderr, "oitbench: --shard auto: shard %s from %s\n", o.shard.text().c_str(),
                   o.shard.source.c_str());
  }
  return run_command(s.registry, s.run);
}

void declare_render(CLI::App& render, CliState& s) {
  add_backend(render, s);
  RenderCommand& r = s.render;
  render.add_option("--scene", r.scene, "Scene name (scenes/NAME.json)");
  render.add_option("--view", r.view, "View named in the scene file");
  render.add_option("--technique", r.technique, "Technique (see: oitbench list, experiment oit)");
  render.add_option("--out,-o", r.out,
                    "Image file (.png); beside it: .pfm (float), -diff8.png, -depth.png, -depth-histogram.csv, .csv");
  render.add_option("--resolution", r.resolution, "WIDTHxHEIGHT");
  render.add_option("--set", r.sets, "Other oit parameters, NAME=VALUE (e.g. nodes=8)")->take_all();
}

int execute_render(const CLI::App&, CliState& s) {
  apply_context(s);
  RunOptions& o = s.run.options;  // render takes run's defaults (shaders, sampling) for its one case
  o.context = s.context;
  check_outputs(o);
  s.render.options = o;
  return render_command(s.registry, s.render);
}

void declare_view(CLI::App& view, CliState& s) {
  viewer::ViewerOptions& v = s.view;
  view.add_option("--scene", v.scene, "Scene name (scenes/NAME.json) or path to a scene .json")->capture_default_str();
  view.add_option("--view", v.view, "View named in the scene file to start from (default: the file's first)");
  view.add_option("--technique", v.technique, "Technique to start with (see: oitbench list, experiment oit)")
      ->capture_default_str();
  view.add_option("--size", v.size, "Window WIDTHxHEIGHT (the cases render at the window's size)")
      ->capture_default_str();
  view.add_option("--detail", v.detail, "Scene size: full, or small (the scene file's small overrides)")
      ->capture_default_str();
  view.add_option("--set", v.sets, "Other oit parameters, NAME=VALUE (e.g. nodes=8, block=16)")->take_all();
  view.add_option("--frames", v.frames, "Render this many frames, then exit 0 (default: until Esc or closed)")
      ->transform(number(whole(0, 100000000)));
  view.add_option("--screenshot", v.screenshot, "Save the last frame, overlay included, as this PNG (also P's file)");
  view.add_option("--keys", v.keys,
                  "Scripted key presses FRAME:KEY,... e.g. \"2:T,4:Z,6:shift+M,8:V\" (tests); "
                  "W/A/S/D/Q/E move as if held for 0.1 s");
  view.add_option("--save-view", v.save_view,
                  "Name for the view V saves (taken: NAME-2, ...; default view-1, view-2, ...)");
  view.add_flag("--gl-debug", v.gl_debug, "Print KHR_debug messages to stderr");
  view.add_option("--memory-limit", s.view_memory_limit,
                  "The most memory a case may hold, as in run (SIZE: 8G, 512M, ...; default: MemAvailable and "
                  "this process's RLIMIT_AS/RLIMIT_DATA): a technique whose estimate is larger is not built")
      ->check(byte_size_validator());
  view.footer(std::string("Keys:\n") + viewer::key_help() +
              "\n\nExit codes: 0 done, 1 a case could not be built or a view/screenshot not saved, 2 usage error,\n"
              "3 no display or no GL context (run under xvfb-run -a).");
}

int execute_view(const CLI::App&, CliState& s) {
  apply_context(s);
  if (!s.view_memory_limit.empty()) s.view.memory_limit = parse_byte_size(s.view_memory_limit);
  return viewer::run_viewer(s.registry, s.view);
}

void declare_nothing(CLI::App&, CliState&) {}

int execute_version(const CLI::App&, CliState&) {
  std::printf("%s\n", version_text().c_str());
  return 0;
}

constexpr Subcommand kSubcommands[] = {
    {"list", "List the experiments with their parameters (or the presets)", declare_list, execute_list},
    {"info", "Show the context: backend, vendor, renderer, limits, extensions", declare_info, execute_info},
    {"run", "Run experiments (the cartesian product of their parameter lists)", declare_run, execute_run},
    {"render",
     "Render one scene view with one OIT technique and write the image (PNG), |image - exact| x 8, the depth "
     "complexity in false colour and its histogram (CSV), plus the case's CSV row",
     declare_render, execute_render},
    {"view",
     "Open a window on one scene, rendered live by the oit experiment's cases: fly camera, keys to switch "
     "technique, BMA, MAX_FRAGS and capture storage, per-pass timings and depth complexity on screen, and a key "
     "that saves the camera as a named view in the scene file. Needs a display (headless: xvfb-run -a)",
     declare_view, execute_view},
    {"version", "Print the version and the build options (like --version)", declare_nothing, execute_version},
};

std::string subcommand_names() {
  std::string names;
  for (const auto& sub : kSubcommands) names += (names.empty() ? "" : ", ") + std::string(sub.name);
  return names;
}

// The first word, where a subcommand is expected, when it is neither an option nor a subcommand.
std::string unknown_subcommand(int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-' || argv[1][0] == '\0') return "";
  for (const auto& sub : kSubcommands)
    if (std::string(argv[1]) == sub.name) return "";
  return argv[1];
}

void describe_app(CLI::App& app) {
  // The techniques of the examples, from the technique table: the first one with nodes, and the default's BMA twin.
  const std::string nodes_technique = oit::techniques_reading("nodes").front();
  std::string image = nodes_technique;
  std::transform(image.begin(), image.end(), image.begin(), [](unsigned char c) { return std::tolower(c); });
  const oit::Technique* bma = oit::bma_twin(oit::technique(oit::default_technique()));
  app.footer(
      "Examples:\n"
      "  oitbench list\n"
      "  oitbench --version\n"
      "  oitbench info --backend egl-device\n"
      "  oitbench run occupancy --quick --out results/occ.csv\n"
      "  oitbench run occupancy --set variant=unrolled --set size=32,33\n"
      "  oitbench run --preset default --out run.csv\n"
      "  oitbench render --scene hairball --view rev --technique " +
      nodes_technique + " --set nodes=8 --out " + image +
      ".png\n"
      "  oitbench view --scene hairball --technique " +
      (bma ? bma->name : oit::default_technique()) + "\n\n" + kExitCodes);
  app.require_subcommand(1);
  app.set_version_flag("--version", version_text(),
                       "Print the version (git describe of the source tree at build time) and the build options");
}

// What a subcommand throws, as the exit code of docs/usage.md's table.
int exit_code_of(const std::function<int()>& execute) {
  const auto fail = [](const std::exception& e, int code, const char* what = "error") {
    std::fprintf(stderr, "oitbench: %s: %s\n", what, e.what());
    return code;
  };
  try {
    return execute();
  } catch (const UsageError& e) {
    return fail(e, 2);
  } catch (const CsvError& e) {
    return fail(e, 2);
  } catch (const FileError& e) {
    return fail(e, 2);
  } catch (const BackendError& e) {
    return fail(e, 3, "cannot create a GL context");
  } catch (const std::exception& e) {
    return fail(e, 1);
  }
}

}  // namespace

int run_cli(int argc, char** argv) {
  CliState state;
  try {
    register_all_experiments(state.registry);
  } catch (const std::logic_error& e) {  // an experiment declares a clashing metric or parameter
    std::fprintf(stderr, "oitbench: internal error registering the experiments: %s\n", e.what());
    return 1;
  }
  CLI::App app{
      "oitbench: GPU microbenchmarks and occupancy studies for order-independent transparency.\n"
      "Runs isolated GL experiments headless (EGL surfaceless by default, Mesa llvmpipe or a real\n"
      "driver), validates every case against a CPU reference and writes tidy CSV."};
  describe_app(app);
  std::vector<std::pair<const Subcommand*, CLI::App*>> subs;
  for (const auto& sub : kSubcommands) {
    auto* cmd = app.add_subcommand(sub.name, sub.help);
    sub.declare(*cmd, state);
    subs.emplace_back(&sub, cmd);
  }
  if (auto word = unknown_subcommand(argc, argv); !word.empty()) {
    std::fprintf(stderr, "oitbench: error: unknown subcommand '%s'; subcommands: %s (see: oitbench --help)\n",
                 word.c_str(), subcommand_names().c_str());
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  for (const auto& [sub, cmd] : subs)
    if (cmd->parsed()) return exit_code_of([&] { return sub->execute(*cmd, state); });
  return 2;  // require_subcommand(1) makes this unreachable
}

}  // namespace oitbench
