// oitbench info: the context this machine gives, what the driver can do, its limits.
#include <cstdio>

#include "app/commands.hpp"

namespace oitbench::app {

int info_command(const ContextOptions& copt) {
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

}  // namespace oitbench::app
