#include "app/cli.hpp"

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "app/commands.hpp"
#include "backends/drivers.hpp"
#include "core/csv.hpp"
#include "core/files.hpp"
#include "core/presets.hpp"
#include "core/provenance.hpp"
#include "core/runner.hpp"
#include "experiments/experiments.hpp"
#include "viewer/viewer.hpp"

namespace oitbench {

using namespace app;

namespace {

constexpr double kMaxTimeoutSeconds = 604800;  // a week
constexpr int kMaxDeviceIndex = 1023;

// `oitbench --version` and `oitbench version`: the version, then the build options.
std::string version_text() {
  std::string s = std::string("oitbench ") + version_string() + "\n" + build_options();
  while (!s.empty() && s.back() == '\n') s.pop_back();
  return s;
}

// --timeout: a finite number of seconds above 0 (CLI11's PositiveNumber lets "nan" through).
CLI::Validator seconds_validator() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        double v = 0;
        size_t pos = 0;
        try {
          v = std::stod(text, &pos);
        } catch (const std::exception&) {
          pos = 0;
        }
        if (pos == 0 || pos != text.size() || !std::isfinite(v) || v <= 0 || v > kMaxTimeoutSeconds)
          return "expected seconds above 0 and at most " + std::to_string(static_cast<int>(kMaxTimeoutSeconds)) +
                 " (a week), got '" + text + "'";
        return "";
      },
      "SECONDS");
}

// The first word that is neither an option nor a subcommand, where a subcommand is expected.
std::string unknown_subcommand(int argc, char** argv, const CLI::App& app) {
  if (argc < 2) return "";
  std::string first = argv[1];
  if (first.empty() || first[0] == '-') return "";
  for (const auto* sub : app.get_subcommands([](const CLI::App*) { return true; }))
    if (sub->get_name() == first) return "";
  return first;
}

constexpr const char* kExitCodes =
    "Exit codes: 0 done (rows may still be invalid: see the status column), 1 errors or timeouts,\n"
    "2 usage error, 3 nothing could run on this driver (all unsupported), 130 interrupted.";

}  // namespace

int run_cli(int argc, char** argv) {
  Registry registry;
  try {
    register_all_experiments(registry);
  } catch (const std::logic_error& e) {  // an experiment declares a clashing metric or parameter
    std::fprintf(stderr, "oitbench: internal error registering the experiments: %s\n", e.what());
    return 1;
  }

  CLI::App app{
      "oitbench: GPU microbenchmarks and occupancy studies for order-independent transparency.\n"
      "Runs isolated GL experiments headless (EGL surfaceless by default, Mesa llvmpipe or a real\n"
      "driver), validates every case against a CPU reference and writes tidy CSV."};
  app.footer(std::string("Examples:\n"
                         "  oitbench list\n"
                         "  oitbench --version\n"
                         "  oitbench info --backend egl-device\n"
                         "  oitbench run occupancy --quick --out results/occ.csv\n"
                         "  oitbench run occupancy --set variant=unrolled --set size=32,33\n"
                         "  oitbench run --preset default --out run.csv\n"
                         "  oitbench render --scene hairball --view rev --technique MLAB --set nodes=8 --out mlab.png\n"
                         "  oitbench view --scene hairball --technique BMA-IS\n\n") +
             kExitCodes);
  app.require_subcommand(1);
  app.set_version_flag("--version", version_text(),
                       "Print the version (git describe of the source tree at build time) and the build options");

  auto* list = app.add_subcommand("list", "List the experiments with their parameters (or the presets)");
  ListOptions lopt;
  lopt.preset_dir = default_preset_dir();
  list->add_flag("--presets", lopt.presets, "List the presets (named grids in presets/*.json)");
  list->add_option("--schema", lopt.schema,
                   "Print the CSV schema (columns with role, type, unit and meaning; statuses) as FORMAT: json");
  list->add_flag("--techniques", lopt.techniques,
                 "List the oit experiment's techniques (family, resolve scheme and sort, parameters read, reference)");
  list->add_flag("--json", lopt.json,
                 "With --techniques: print the table as JSON (what scripts/techniques.json holds)");
  list->add_option("--presets-dir", lopt.preset_dir, "Preset directory (default: the source tree's presets/)");

  ContextOptions copt;
  std::string driver = "default";
  auto add_backend = [&](CLI::App* cmd) {
    cmd->add_option("--backend", copt.backend, "Context backend: egl (surfaceless, default), egl-device, osmesa, glfw")
        ->check(CLI::IsMember(compiled_backends()));
    cmd->add_option("--device", copt.device, "EGL device index for --backend egl-device (see info)")
        ->check(CLI::Range(0, kMaxDeviceIndex));
    cmd->add_flag("--gl-debug", copt.debug, "Print KHR_debug messages to stderr");
    cmd->add_option("--driver", driver,
                    "GL driver: default (what the loader gives), llvmpipe, zink (GL on Vulkan on lavapipe), softpipe, "
                    "egl-device-N; see: oitbench info --drivers");
  };
  add_backend(list);  // list --presets creates a context to say which size applies here
  auto* info = app.add_subcommand("info", "Show the context: backend, vendor, renderer, limits, extensions");
  add_backend(info);
  bool info_drivers = false;
  info->add_flag("--drivers", info_drivers,
                 "List the GL drivers this machine offers (each tried in a child process): name, renderer, version, "
                 "whether oitbench can run on it");

  auto* run = app.add_subcommand("run", "Run experiments (the cartesian product of their parameter lists)");
  run->footer(std::string("The CSV gets one row per case and pass (see README, 'CSV schema'). Rows are written as each "
                          "case\n(or interleaved group) finishes: Ctrl-C leaves every finished row.\n") +
              kExitCodes);
  add_backend(run);
  RunCommand rc;
  rc.preset_dir = lopt.preset_dir;
  RunOptions& ropt = rc.options;
  ropt.shader_root = default_shader_root();
  run->add_option("experiments", rc.experiments, "Experiment names, or 'all' (see: oitbench list)");
  run->add_option("--set", rc.sets,
                  "NAME=V1,V2,... (integer ranges A..B or A..B:STEP); repeatable. A parameter "
                  "scoped to some techniques or variants must apply to at least one selected case")
      ->take_all();
  run->add_option("--preset", rc.preset, "Run a named grid from presets/ (see: oitbench list --presets)");
  run->add_option("--resolution", rc.resolution, "Render target WIDTHxHEIGHT (default: each experiment's own)");
  run->add_option("--reps", ropt.reps,
                  "Timed repetitions per case: a fixed count (default: until --target-ci is reached; --quick 3)")
      ->check(CLI::Range(1, 100000));
  run->add_option("--warmup", ropt.warmup, "Untimed repetitions first (default 1)")->check(CLI::Range(0, 1000));
  run->add_flag("--quick", ropt.quick, "Each experiment's small grid and resolution: finishes in seconds");
  run->add_option("--out,-o", ropt.out, "CSV file (appends when the header matches; '-' = stdout)");
  run->add_option("--raw", ropt.raw, "Also write every repetition (one row per sample) to this CSV");
  run->add_option("--timer", ropt.timer,
                  "Primary clock: auto (CPU on software renderers, GPU queries elsewhere), cpu, gpu")
      ->check(CLI::IsMember({"auto", "cpu", "gpu"}));
  bool no_interleave = false, no_progress = false, no_program_cache = false;
  run->add_flag("--sync-passes", ropt.sync_passes,
                "glFinish around every timed pass on hardware drivers too (serialises the pipeline; software "
                "renderers always do it). Default there: passes back to back, timed by GL_TIME_ELAPSED queries");
  run->add_flag("--no-program-cache", no_program_cache,
                "Compile every program from source (to measure compile time); default: reuse linked programs "
                "from ~/.cache/oitbench/programs (glGetProgramBinary, keyed on sources, defines and driver)");
  run->add_flag("--no-interleave", no_interleave,
                "Run each case's repetitions back to back (default: A B C A B C ...)");
  run->add_option("--isolate", ropt.isolate,
                  "Run cases in child processes under the watchdog: auto (hang-prone experiments), always, never")
      ->check(CLI::IsMember({"auto", "always", "never"}));
  run->add_option("--timeout", ropt.timeout_s, "Watchdog: seconds a case may take before it is killed (status timeout)")
      ->check(seconds_validator());
  run->add_option("--max-cases", ropt.max_cases,
                  "The most cases one run may have (default 100000), checked before anything is built")
      ->check(CLI::Range(static_cast<size_t>(1), static_cast<size_t>(100000000)));
  run->add_flag("--no-progress", no_progress, "No progress line on stderr");
  run->add_option(
      "--shaders", ropt.shader_root,
      "Shader directory (default: shaders/ found from the binary, else the source tree's; see: oitbench info)");
  run->add_option("--presets-dir", rc.preset_dir,
                  "Preset directory (default: presets/ found from the binary, else the source tree's)");
  // Sample sizes, the stopping rule and paired speedups (docs/measurement.md#samples-sized-by-their-statistics).
  double target_ci_pct = ropt.sampling.target_ci * 100;
  ropt.sampling.max_case_s = 10;  // a 2-core machine's reference runs: 10 timed seconds per case at most
  const char* sizing = "Samples and stopping";
  run->add_option("--target-ci", target_ci_pct,
                  "Repeat until the 95% interval of each case's median is within +-this % (default 3); --reps N "
                  "fixes the count instead")
      ->check(CLI::Range(0.01, 1000.0))
      ->group(sizing);
  run->add_option("--max-reps", ropt.sampling.max_reps, "At most this many timed repetitions per case (default 30)")
      ->check(CLI::Range(2, 100000))
      ->group(sizing);
  run->add_option("--max-case-s", ropt.sampling.max_case_s,
                  "At most this many timed seconds per case (a group of n cases: n times it; default 10)")
      ->check(CLI::PositiveNumber)
      ->group(sizing);
  run->add_option("--min-sample-ms", ropt.sampling.min_sample_ms,
                  "A sample runs the case's repetition often enough to last this long (default 20; 0: once)")
      ->check(CLI::NonNegativeNumber)
      ->group(sizing);
  run->add_option("--max-sample-ms", ropt.sampling.max_sample_ms,
                  "A repetition longer than this runs fewer units of scalable work (occupancy's draws), times "
                  "scaled back (default 500; 0: never)")
      ->check(CLI::NonNegativeNumber)
      ->group(sizing);
  run->add_option("--baseline", rc.baseline,
                  "NAME=VALUE ...: the case each speedup divides by, run in every interleaved group of the cases "
                  "it is the baseline of (e.g. technique=BASE-IS); replaces a preset's")
      ->take_all()
      ->group(sizing);
  std::string shard_text;
  const char* fleet = "Fleets and CI (docs/ci.md)";
  run->add_option("--shard", shard_text,
                  "I/N: run the I-th of N disjoint parts of the grid (1 <= I <= N; together the whole grid, an "
                  "interleaved group and its baseline never split); auto: I and N from a Slurm array, a Kubernetes "
                  "Indexed Job or GitLab's parallel:")
      ->group(fleet);
  run->add_option("--preset-name", ropt.preset_name, "Recorded in the preset column")->group("");
  run->add_flag("--isolated-child", ropt.isolated_child, "Set by the parent for an isolated case")->group("");

  auto* render =
      app.add_subcommand("render",
                         "Render one scene view with one OIT technique and write the image (PNG), |image - exact| x 8, "
                         "the depth complexity in false colour and its histogram (CSV), plus the case's CSV row");
  add_backend(render);
  RenderCommand rn;
  render->add_option("--scene", rn.scene, "Scene name (scenes/NAME.json)");
  render->add_option("--view", rn.view, "View named in the scene file");
  render->add_option("--technique", rn.technique, "Technique (see: oitbench list, experiment oit)");
  render->add_option("--out,-o", rn.out,
                     "Image file (.png); beside it: .pfm (float), -diff8.png, -depth.png, -depth-histogram.csv, .csv");
  render->add_option("--resolution", rn.resolution, "WIDTHxHEIGHT");
  render->add_option("--set", rn.sets, "Other oit parameters, NAME=VALUE (e.g. nodes=8)")->take_all();

  auto* view = app.add_subcommand(
      "view",
      "Open a window on one scene, rendered live by the oit experiment's cases: fly camera, keys to switch "
      "technique, BMA, MAX_FRAGS and capture storage, per-pass timings and depth complexity on screen, and a key "
      "that saves the camera as a named view in the scene file. Needs a display (headless: xvfb-run -a)");
  viewer::ViewerOptions v_opt;
  view->add_option("--scene", v_opt.scene, "Scene name (scenes/NAME.json) or path to a scene .json")
      ->capture_default_str();
  view->add_option("--view", v_opt.view, "View named in the scene file to start from (default: the file's first)");
  view->add_option("--technique", v_opt.technique, "Technique to start with (see: oitbench list, experiment oit)")
      ->capture_default_str();
  view->add_option("--size", v_opt.size, "Window WIDTHxHEIGHT (the cases render at the window's size)")
      ->capture_default_str();
  view->add_option("--detail", v_opt.detail, "Scene size: full, or small (the scene file's small overrides)")
      ->capture_default_str();
  view->add_option("--set", v_opt.sets, "Other oit parameters, NAME=VALUE (e.g. nodes=8, block=16)")->take_all();
  view->add_option("--frames", v_opt.frames, "Render this many frames, then exit 0 (default: until Esc or closed)")
      ->check(CLI::Range(0, 100000000));
  view->add_option("--screenshot", v_opt.screenshot,
                   "Save the last frame, overlay included, as this PNG (also P's file)");
  view->add_option("--keys", v_opt.keys,
                   "Scripted key presses FRAME:KEY,... e.g. \"2:T,4:Z,6:shift+M,8:V\" (tests); "
                   "W/A/S/D/Q/E move as if held for 0.1 s");
  view->add_option("--save-view", v_opt.save_view,
                   "Name for the view V saves (taken: NAME-2, ...; default view-1, view-2, ...)");
  view->add_flag("--gl-debug", v_opt.gl_debug, "Print KHR_debug messages to stderr");
  view->footer(std::string("Keys:\n") + viewer::key_help() +
               "\n\nExit codes: 0 done, 1 a case could not be built or a view/screenshot not saved, 2 usage error,\n"
               "3 no display or no GL context (run under xvfb-run -a).");

  auto* version = app.add_subcommand("version", "Print the version and the build options (like --version)");

  if (auto word = unknown_subcommand(argc, argv, app); !word.empty()) {
    std::fprintf(stderr,
                 "oitbench: error: unknown subcommand '%s'; subcommands: list, info, run, render, view, version "
                 "(see: oitbench --help)\n",
                 word.c_str());
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }

  try {
    if (*version) {
      std::printf("%s\n", version_text().c_str());
      return 0;
    }
    if (*info && info_drivers) return drivers_command(copt);
    if (!*list || lopt.presets) {  // list --presets creates a context too
      try {
        apply_driver(find_driver(driver), copt);
      } catch (const BackendError& e) {
        throw UsageError(e.what());
      }
      if (copt.device != 0 && copt.backend != "egl-device")
        throw UsageError("--device " + std::to_string(copt.device) +
                         " applies to --backend egl-device only (this is --backend " + copt.backend +
                         "); see: oitbench info --drivers");
    }
    if (*list) return list_command(registry, lopt, copt);
    if (*info) return info_command(copt);
    if (*view) return viewer::run_viewer(registry, v_opt);
    ropt.context = copt;
    check_output_file(ropt.out, "--out");
    if (!ropt.raw.empty()) {
      check_output_file(ropt.raw, "--raw");
      if (ropt.raw == ropt.out ||
          (ropt.out != "-" && std::filesystem::exists(ropt.out) && std::filesystem::exists(ropt.raw) &&
           std::filesystem::equivalent(ropt.out, ropt.raw)))
        throw UsageError("--raw and --out name the same file (" + ropt.raw + "); give two files");
    }
    if (*render) {
      rn.options = ropt;
      return render_command(registry, rn);
    }
    ropt.reps_given = run->count("--reps") > 0;
    ropt.sampling.adaptive = true;  // unless --reps, a preset entry's reps or --quick fix the count
    ropt.sampling.target_ci = target_ci_pct / 100;
    ropt.warmup_given = run->count("--warmup") > 0;
    ropt.interleave = !no_interleave;
    ropt.program_cache = !no_program_cache;
    ropt.progress = !no_progress;
    if (!shard_text.empty()) {
      ropt.shard = parse_shard(shard_text);
      if (!ropt.shard.source.empty())
        std::fprintf(stderr, "oitbench: --shard auto: shard %s from %s\n", ropt.shard.text().c_str(),
                     ropt.shard.source.c_str());
    }
    return run_command(registry, rc);
  } catch (const UsageError& e) {
    std::fprintf(stderr, "oitbench: error: %s\n", e.what());
    return 2;
  } catch (const CsvError& e) {
    std::fprintf(stderr, "oitbench: error: %s\n", e.what());
    return 2;
  } catch (const FileError& e) {
    std::fprintf(stderr, "oitbench: error: %s\n", e.what());
    return 2;
  } catch (const BackendError& e) {
    std::fprintf(stderr, "oitbench: cannot create a GL context: %s\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "oitbench: error: %s\n", e.what());
    return 1;
  }
}

}  // namespace oitbench
