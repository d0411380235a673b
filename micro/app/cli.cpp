#include "app/cli.hpp"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "experiments/experiments.hpp"
#include "core/csv.hpp"
#include "core/presets.hpp"
#include "core/runner.hpp"
#include "viewer/viewer.hpp"

namespace oitbench {

namespace {

constexpr const char* kExitCodes =
    "Exit codes: 0 done (rows may still be invalid: see the status column), 1 errors or timeouts,\n"
    "2 usage error, 3 nothing could run on this driver (all unsupported), 130 interrupted.";

void print_list(const Registry& registry, bool presets, const std::string& preset_dir) {
  if (presets) {
    std::printf("Presets in %s (run with: oitbench run --preset NAME):\n", preset_dir.c_str());
    for (const auto& p : list_presets(preset_dir)) {
      std::printf("  %-18s %s\n", p.name.c_str(), p.description.c_str());
      for (const auto& r : p.runs) {
        std::printf("      %s", r.experiment.c_str());
        for (const auto& [k, v] : r.overrides) std::printf(" %s=%zu value(s)", k.c_str(), v.size());
        std::printf("\n");
      }
    }
    return;
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
    }
    std::printf("\n");
  }
}

int print_info(const ContextOptions& copt) {
  std::printf("backends in this build: ");
  for (const auto& b : compiled_backends()) std::printf("%s ", b.c_str());
#ifndef OITBENCH_HAVE_OSMESA
  std::printf("(osmesa: absent, not found at build time)");
#endif
  std::printf("\n");
  if (copt.backend == "egl-device") {
    auto devices = list_egl_devices();
    std::printf("EGL devices: %zu\n", devices.size());
    for (const auto& d : devices)
      std::printf("  --device %d: %s%s%s\n", d.index, d.extensions.c_str(),
                  d.drm_file.empty() ? "" : (" " + d.drm_file).c_str(),
                  d.renderer.empty() ? "" : (" " + d.renderer).c_str());
  }
  auto ctx = create_context(copt);
  auto gl = GlInfo::query();
  auto yes = [](bool b) { return b ? "yes" : "no"; };
  std::printf("backend:        %s\ndevice:         %s\n", ctx->backend().c_str(), ctx->device().c_str());
  std::printf("GL_VENDOR:      %s\nGL_RENDERER:    %s\nGL_VERSION:     %s\nGLSL:           %s\n", gl.vendor.c_str(),
              gl.renderer.c_str(), gl.version.c_str(), gl.glsl_version.c_str());
  std::printf("software renderer: %s (primary timer: %s)\n", yes(gl.is_software_renderer()),
              gl.is_software_renderer() ? "CPU clock around glFinish" : "GL_TIME_ELAPSED queries");
  std::printf("compute shaders: %s\ntimer queries:   %s\nimage atomics:   %s\nfragment_shader_interlock: %s",
              yes(gl.has_compute()), yes(gl.has_timer_query()), yes(gl.has_version(4, 2)),
              yes(gl.has_fragment_shader_interlock()));
  for (const char* e : {"GL_ARB_fragment_shader_interlock", "GL_NV_fragment_shader_interlock",
                        "GL_INTEL_fragment_shader_ordering"})
    if (gl.has_extension(e)) std::printf(" (%s)", e);
  std::printf("\n");
  for (const char* e : {"GL_ARB_shader_clock", "GL_ARB_shader_ballot", "GL_ARB_gpu_shader_int64",
                        "GL_NV_shader_atomic_int64", "GL_ARB_bindless_texture", "GL_KHR_debug",
                        "GL_ARB_get_program_binary", "GL_ARB_pipeline_statistics_query"})
    std::printf("%-34s %s\n", e, yes(gl.has_extension(e)));
  for (const auto& [k, v] : gl.limits) std::printf("%-40s %lld\n", k.c_str(), v);
  std::printf("extensions: %zu\n", gl.extensions.size());
  return 0;
}

}  // namespace

int run_cli(int argc, char** argv) {
  Registry registry;
  register_all_experiments(registry);

  CLI::App app{"oitbench: GPU microbenchmarks and occupancy studies for order-independent transparency.\n"
               "Runs isolated GL experiments headless (EGL surfaceless by default, Mesa llvmpipe or a real\n"
               "driver), validates every case against a CPU reference and writes tidy CSV."};
  app.footer(std::string("Examples:\n"
                         "  oitbench list\n"
                         "  oitbench info --backend egl-device\n"
                         "  oitbench run occupancy --quick --out results/occ.csv\n"
                         "  oitbench run occupancy --set variant=unrolled --set size=32,33\n"
                         "  oitbench run --preset default --out run.csv\n"
                         "  oitbench render --scene hairball --view rev --technique MLAB --set nodes=8 --out mlab.png\n"
                         "  oitbench view --scene hairball --technique BMA-IS\n\n") +
             kExitCodes);
  app.require_subcommand(1);

  auto* list = app.add_subcommand("list", "List the experiments with their parameters (or the presets)");
  bool list_presets_flag = false;
  list->add_flag("--presets", list_presets_flag, "List the presets (named grids in presets/*.json)");

  ContextOptions copt;
  auto add_backend = [&](CLI::App* cmd) {
    cmd->add_option("--backend", copt.backend, "Context backend: egl (surfaceless, default), egl-device, osmesa, glfw")
        ->check(CLI::IsMember(compiled_backends()));
    cmd->add_option("--device", copt.device, "EGL device index for --backend egl-device (see info)")->check(CLI::NonNegativeNumber);
    cmd->add_flag("--gl-debug", copt.debug, "Print KHR_debug messages to stderr");
  };
  auto* info = app.add_subcommand("info", "Show the context: backend, vendor, renderer, limits, extensions");
  add_backend(info);

  auto* run = app.add_subcommand("run", "Run experiments (the cartesian product of their parameter lists)");
  run->footer(std::string("The CSV gets one row per case and pass (see README, 'CSV schema'). Rows are written as each "
                          "case\n(or interleaved group) finishes: Ctrl-C leaves every finished row.\n") +
              kExitCodes);
  add_backend(run);
  std::vector<std::string> names, sets;
  std::string preset, resolution, preset_dir = default_preset_dir();
  RunOptions ropt;
  ropt.shader_root = default_shader_root();
  run->add_option("experiments", names, "Experiment names, or 'all' (see: oitbench list)");
  run->add_option("--set", sets, "NAME=V1,V2,... (integer ranges A..B or A..B:STEP); repeatable")->take_all();
  run->add_option("--preset", preset, "Run a named grid from presets/ (see: oitbench list --presets)");
  run->add_option("--resolution", resolution, "Render target WIDTHxHEIGHT (default: each experiment's own)");
  run->add_option("--reps", ropt.reps, "Timed repetitions per case (default 5; --quick 3)")->check(CLI::Range(1, 100000));
  run->add_option("--warmup", ropt.warmup, "Untimed repetitions first (default 1)")->check(CLI::Range(0, 1000));
  run->add_flag("--quick", ropt.quick, "Each experiment's small grid and resolution: finishes in seconds");
  run->add_option("--out,-o", ropt.out, "CSV file (appends when the header matches; '-' = stdout)");
  run->add_option("--raw", ropt.raw, "Also write every repetition (one row per sample) to this CSV");
  run->add_option("--timer", ropt.timer, "Primary clock: auto (CPU on software renderers, GPU queries elsewhere), cpu, gpu")
      ->check(CLI::IsMember({"auto", "cpu", "gpu"}));
  bool no_interleave = false, no_progress = false, no_program_cache = false;
  run->add_flag("--no-program-cache", no_program_cache,
                "Compile every program from source (to measure compile time); default: reuse linked programs "
                "from ~/.cache/oitbench/programs (glGetProgramBinary, keyed on sources, defines and driver)");
  run->add_flag("--no-interleave", no_interleave, "Run each case's repetitions back to back (default: A B C A B C ...)");
  run->add_option("--isolate", ropt.isolate, "Run cases in child processes under the watchdog: auto (hang-prone experiments), always, never")
      ->check(CLI::IsMember({"auto", "always", "never"}));
  run->add_option("--timeout", ropt.timeout_s, "Watchdog: seconds a case may take before it is killed (status timeout)")
      ->check(CLI::PositiveNumber);
  run->add_flag("--no-progress", no_progress, "No progress line on stderr");
  run->add_option("--shaders", ropt.shader_root, "Shader directory (default: the source tree's shaders/)");
  run->add_option("--presets-dir", preset_dir, "Preset directory (default: the source tree's presets/)");
  run->add_option("--preset-name", ropt.preset_name, "Recorded in the preset column")->group("");
  run->add_flag("--isolated-child", ropt.isolated_child, "Set by the parent for an isolated case")->group("");

  auto* render = app.add_subcommand(
      "render", "Render one scene view with one OIT technique and write the image (PNG), |image - exact| x 8, "
                "the depth complexity in false colour and its histogram (CSV), plus the case's CSV row");
  add_backend(render);
  std::string r_scene = "planes", r_view = "fwd", r_technique = "BASE-IS", r_out = "render.png", r_resolution = "512x512";
  std::vector<std::string> r_sets;
  render->add_option("--scene", r_scene, "Scene name (scenes/NAME.json)");
  render->add_option("--view", r_view, "View named in the scene file");
  render->add_option("--technique", r_technique, "Technique (see: oitbench list, experiment oit)");
  render->add_option("--out,-o", r_out, "Image file (.png); beside it: .pfm (float), -diff8.png, -depth.png, -depth-histogram.csv, .csv");
  render->add_option("--resolution", r_resolution, "WIDTHxHEIGHT");
  render->add_option("--set", r_sets, "Other oit parameters, NAME=VALUE (e.g. nodes=8)")->take_all();

  auto* view = app.add_subcommand(
      "view", "Open a window on one scene, rendered live by the oit experiment's cases: fly camera, keys to switch "
              "technique, BMA, MAX_FRAGS and capture storage, per-pass timings and depth complexity on screen, and a key "
              "that saves the camera as a named view in the scene file. Needs a display (headless: xvfb-run -a)");
  viewer::ViewerOptions v_opt;
  view->add_option("--scene", v_opt.scene, "Scene name (scenes/NAME.json) or path to a scene .json")->capture_default_str();
  view->add_option("--view", v_opt.view, "View named in the scene file to start from (default: the file's first)");
  view->add_option("--technique", v_opt.technique, "Technique to start with (see: oitbench list, experiment oit)")
      ->capture_default_str();
  view->add_option("--size", v_opt.size, "Window WIDTHxHEIGHT (the cases render at the window's size)")->capture_default_str();
  view->add_option("--detail", v_opt.detail, "Scene size: full, or small (the scene file's small overrides)")
      ->capture_default_str();
  view->add_option("--set", v_opt.sets, "Other oit parameters, NAME=VALUE (e.g. nodes=8, block=16)")->take_all();
  view->add_option("--frames", v_opt.frames, "Render this many frames, then exit 0 (default: until Esc or closed)")
      ->check(CLI::NonNegativeNumber);
  view->add_option("--screenshot", v_opt.screenshot, "Save the last frame, overlay included, as this PNG (also P's file)");
  view->add_option("--keys", v_opt.keys, "Scripted key presses FRAME:KEY,... e.g. \"2:T,4:Z,6:shift+M,8:V\" (tests); "
                                         "W/A/S/D/Q/E move as if held for 0.1 s");
  view->add_option("--save-view", v_opt.save_view, "Name for the view V saves (taken: NAME-2, ...; default view-1, view-2, ...)");
  view->add_flag("--gl-debug", v_opt.gl_debug, "Print KHR_debug messages to stderr");
  view->footer(std::string("Keys:\n") + viewer::key_help() +
               "\n\nExit codes: 0 done, 1 a case could not be built or a view/screenshot not saved, 2 usage error,\n"
               "3 no display or no GL context (run under xvfb-run -a).");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }

  try {
    if (*list) {
      print_list(registry, list_presets_flag, preset_dir);
      return 0;
    }
    if (*info) return print_info(copt);
    if (*view) return viewer::run_viewer(registry, v_opt);
    if (*render) {
      std::string stem = r_out.ends_with(".png") ? r_out.substr(0, r_out.size() - 4) : r_out;
      RunRequest req{"oit", {{"scene", {r_scene}}, {"view", {r_view}}, {"technique", {r_technique}}, {"dump", {stem}}},
                     parse_resolution(r_resolution), 1, 0};
      for (const auto& s : r_sets) {
        auto [k, v] = parse_set_option(s);
        if (v.size() != 1) throw UsageError("render: --set " + k + " takes one value");
        req.overrides[k] = v;
      }
      ropt.context = copt;
      ropt.out = stem + ".csv";
      ropt.progress = false;
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

    ropt.context = copt;
    ropt.reps_given = run->count("--reps") > 0;
    ropt.warmup_given = run->count("--warmup") > 0;
    ropt.interleave = !no_interleave;
    ropt.program_cache = !no_program_cache;
    ropt.progress = !no_progress;
    if (!resolution.empty()) ropt.resolution = parse_resolution(resolution);
    std::map<std::string, std::vector<std::string>> overrides;
    for (const auto& s : sets) {
      auto [k, v] = parse_set_option(s);
      overrides[k] = v;
    }
    std::vector<RunRequest> requests;
    if (!preset.empty()) {
      if (!names.empty()) throw UsageError("give either --preset or experiment names, not both");
      auto p = load_preset(preset_dir, preset);
      if (ropt.preset_name.empty()) ropt.preset_name = p.name;
      requests = p.runs;
      for (auto& r : requests)
        for (const auto& [k, v] : overrides) r.overrides[k] = v;
    } else {
      if (names.empty())
        throw UsageError("run: name an experiment, 'all' or --preset NAME; experiments: " + registry.names());
      for (const auto& n : names) {
        if (n == "all") {
          for (const auto& e : registry.all()) requests.push_back({e->name(), {}, {}, {}, {}});
        } else {
          requests.push_back({n, {}, {}, {}, {}});
        }
      }
      // With several experiments a --set applies where the parameter exists; it must exist somewhere.
      for (const auto& [k, v] : overrides) {
        bool used = false;
        for (auto& r : requests) {
          const auto* e = registry.find(r.experiment);
          if (!e) continue;
          for (const auto& p : registry.params_of(*e))
            if (p.name == k) {
              r.overrides[k] = v;
              used = true;
            }
        }
        if (!used && requests.size() > 1)
          throw UsageError("no selected experiment has a parameter '" + k + "' (see: oitbench list)");
        if (!used) requests[0].overrides[k] = v;  // check_requests names the valid parameters
      }
    }
    return run_experiments(registry, requests, ropt);
  } catch (const UsageError& e) {
    std::fprintf(stderr, "oitbench: error: %s\n", e.what());
    return 2;
  } catch (const CsvError& e) {
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
