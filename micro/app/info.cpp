// oitbench info: the context this machine gives, what the driver can do, its limits.
#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "app/commands.hpp"
#include "backends/drivers.hpp"
#include "core/data_dirs.hpp"
#include "core/gpu_state.hpp"
#include "core/provenance.hpp"

namespace oitbench::app {

int info_command(const ContextOptions& copt) {
  std::printf("backends in this build: ");
  for (const auto& b : compiled_backends()) std::printf("%s ", b.c_str());
#ifndef OITBENCH_HAVE_OSMESA
  std::printf("(osmesa: absent, not found at build time)");
#endif
  std::printf("\n");
  std::printf("oitbench:       %s\n", version_string());
  for (const char* kind : {"shaders", "scenes", "presets"}) {
    auto found = find_data_dir(kind);
    std::printf("%-15s %s (%s)\n", (std::string(kind) + ":").c_str(), found.path.c_str(), found.from.c_str());
  }
  if (copt.backend == "egl-device") {
    auto devices = list_egl_devices();
    std::printf("EGL devices: %zu\n", devices.size());
    for (const auto& d : devices)
      std::printf("  --device %d: %s%s%s%s%s%s\n", d.index, d.extensions.c_str(),
                  d.cuda < 0 ? "" : (" cuda:" + std::to_string(d.cuda)).c_str(),
                  d.drm_file.empty() ? "" : (" " + d.drm_file).c_str(),
                  d.render_node.empty() ? "" : (" " + d.render_node).c_str(),
                  d.pci_bus.empty() ? "" : (" PCI " + d.pci_bus).c_str(),
                  d.renderer.empty() ? "" : (" " + d.renderer).c_str());
  }
  auto ctx = create_context(copt);
  auto gl = GlInfo::query();
  auto yes = [](bool b) { return b ? "yes" : "no"; };
  std::printf("backend:        %s\ndevice:         %s\ndriver:         %s (--driver %s)\n", ctx->backend().c_str(),
              ctx->device().c_str(), driver_slug(gl).c_str(), copt.driver.c_str());
  std::printf("GL_VENDOR:      %s\nGL_RENDERER:    %s\nGL_VERSION:     %s\nGLSL:           %s\n", gl.vendor.c_str(),
              gl.renderer.c_str(), gl.version.c_str(), gl.glsl_version.c_str());
  std::printf("software renderer: %s (primary timer: %s)\n", yes(gl.is_software_renderer()),
              gl.is_software_renderer() ? "CPU clock around glFinish" : "GL_TIME_ELAPSED queries");
  std::printf("compute shaders: %s\ntimer queries:   %s\nimage atomics:   %s\nfragment_shader_interlock: %s",
              yes(gl.has_compute()), yes(gl.has_timer_query()), yes(gl.has_version(4, 2)),
              yes(gl.has_fragment_shader_interlock()));
  for (const char* e :
       {"GL_ARB_fragment_shader_interlock", "GL_NV_fragment_shader_interlock", "GL_INTEL_fragment_shader_ordering"})
    if (gl.has_extension(e)) std::printf(" (%s)", e);
  std::printf("\n");
  for (const char* e :
       {"GL_ARB_shader_clock", "GL_ARB_shader_ballot", "GL_ARB_gpu_shader_int64", "GL_NV_shader_atomic_int64",
        "GL_ARB_bindless_texture", "GL_KHR_debug", "GL_ARB_get_program_binary", "GL_ARB_pipeline_statistics_query"})
    std::printf("%-34s %s\n", e, yes(gl.has_extension(e)));
  if (auto gpu = GpuMonitor::for_gl_context(gl.vendor, gl.renderer); gpu.active()) {
    auto r = gpu.read();
    auto num = [](const auto& v, const char* unit) {
      return v ? std::to_string(static_cast<long long>(std::llround(static_cast<double>(*v)))) + unit : "?";
    };
    std::printf("GPU state (NVML): %s, driver %s, SM %s, memory %s, %s, %s\n", gpu.device_name().c_str(),
                gpu.driver_version().c_str(), num(r.sm_clock_mhz, " MHz").c_str(), num(r.mem_clock_mhz, " MHz").c_str(),
                num(r.temperature_c, " C").c_str(), num(r.power_w, " W").c_str());
  } else {
    std::printf("GPU state (NVML): none (%s)\n", gpu.why_inactive().c_str());
  }
  for (const auto& [k, v] : gl.limits) std::printf("%-40s %lld\n", k.c_str(), v);
  std::printf("extensions: %zu\n", gl.extensions.size());
  return 0;
}

}  // namespace oitbench::app

namespace oitbench::app {

namespace {

// Runs `exe info --driver NAME` and returns its exit code and output (stdout and stderr together).
std::pair<int, std::string> probe_driver(const std::string& exe, const std::string& name) {
  std::string cmd = "'" + exe + "' info --driver '" + name + "' 2>&1";
  std::string out;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return {-1, "cannot start " + exe};
  char buf[4096];
  while (size_t n = fread(buf, 1, sizeof buf, p)) out.append(buf, n);
  int status = pclose(p);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

std::string line_value(const std::string& text, const std::string& key) {
  auto at = text.find(key);
  if (at == std::string::npos) return "";
  auto start = text.find_first_not_of(' ', at + key.size());
  auto end = text.find('\n', start);
  return text.substr(start, end == std::string::npos ? std::string::npos : end - start);
}

}  // namespace

int drivers_command(const ContextOptions&) {
  std::error_code ec;
  std::string exe = std::filesystem::read_symlink("/proc/self/exe", ec).string();
  if (ec) throw std::runtime_error("cannot find the oitbench binary (/proc/self/exe)");
  std::vector<DriverSpec> drivers = known_drivers();
  for (const auto& d : list_egl_devices())
    drivers.push_back(
        {"egl-device-" + std::to_string(d.index),
         "EGL device " + std::to_string(d.index) + ": " + d.extensions + (d.drm_file.empty() ? "" : " " + d.drm_file),
         {},
         "egl-device",
         d.index});
  std::printf("GL drivers on this machine (select one with --driver NAME; each tried in a child process):\n\n");
  int usable = 0;
  for (const auto& d : drivers) {
    auto [code, out] = probe_driver(exe, d.name);
    std::string renderer = line_value(out, "GL_RENDERER:"), version = line_value(out, "GL_VERSION:");
    std::printf("%-14s %s\n", d.name.c_str(), d.description.c_str());
    if (code == 0 && !renderer.empty()) {
      ++usable;
      std::printf("%-14s ok: %s, OpenGL %s\n", "", renderer.c_str(), version.c_str());
    } else {
      std::string why = line_value(out, "oitbench: ");
      if (why.empty()) why = "exit code " + std::to_string(code);
      std::printf("%-14s %s: %s\n", "",
                  out.find("oitbench needs a 4.5 core context") != std::string::npos ? "unsupported" : "not available",
                  why.c_str());
    }
  }
  std::printf("\n%d usable driver(s). Rows record the driver in the `driver` column.\n", usable);
  return usable > 0 ? 0 : 3;
}

}  // namespace oitbench::app
