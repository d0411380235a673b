#pragma once
// One interface over the ways of getting a GL 4.5+ core context: EGL surfaceless (default,
// headless, Mesa llvmpipe or a real driver), EGL device (pick a GPU), OSMesa, and a GLFW window.
#include <map>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "backends/device_select.hpp"

namespace oitbench {

class BackendError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// What the running context can do: the facts `oitbench info` prints and experiments check.
struct GlInfo {
  std::string vendor, renderer, version, glsl_version;
  int major = 0, minor = 0;
  std::set<std::string> extensions;
  std::map<std::string, long long> limits;  // GL_MAX_* values by name
  bool has_extension(const std::string& name) const { return extensions.count(name) > 0; }
  bool has_version(int maj, int min) const { return major > maj || (major == maj && minor >= min); }
  bool has_compute() const { return has_version(4, 3); }
  bool has_timer_query() const { return has_version(3, 3) || has_extension("GL_ARB_timer_query"); }
  bool has_fragment_shader_interlock() const;
  // A CPU rasterizer (llvmpipe, softpipe, swrast, SwiftShader): GL timer queries are not trusted there.
  bool is_software_renderer() const;
  long long limit(const std::string& name) const;
  static GlInfo query();  // from the current context
};

// The driver offers a GL version below oitbench's 4.5 core: cases are `unsupported`, not errors.
class ContextUnsupported : public BackendError {
 public:
  ContextUnsupported(const std::string& what, std::string offered) : BackendError(what), offered_(std::move(offered)) {}
  const std::string& offered() const { return offered_; }  // the GL_VERSION it gave instead

 private:
  std::string offered_;
};

struct ContextOptions {
  std::string backend = "egl";     // egl | egl-device | osmesa | glfw
  std::string driver = "default";  // backends/drivers.hpp: set by apply_driver
  int device = 0;                  // egl-device: index into the EGL device list
  int width = 800, height = 600;
  bool visible = false;  // glfw: show the window
  bool debug = false;    // KHR_debug output to stderr
};

class Context {
 public:
  virtual ~Context() = default;
  virtual std::string backend() const = 0;
  virtual std::string device() const = 0;  // which display/device the context runs on, in words
  virtual void swap_buffers() {}
  virtual bool window_should_close() { return false; }
  virtual void* native_window() { return nullptr; }
};

struct DeviceInfo : DeviceDescription {  // index, CUDA ordinal, DRM nodes, PCI bus (device_select.hpp)
  std::string extensions;                // EGL device extensions, e.g. EGL_MESA_device_software
  std::string renderer;                  // EGL_RENDERER_EXT where known
};

std::vector<std::string> compiled_backends();
std::unique_ptr<Context> create_context(const ContextOptions& options);  // throws BackendError
std::vector<DeviceInfo> list_egl_devices();

// Per-backend constructors (defined in their own files).
std::unique_ptr<Context> create_egl_context(const ContextOptions& options);
std::unique_ptr<Context> create_osmesa_context(const ContextOptions& options);
std::unique_ptr<Context> create_glfw_context(const ContextOptions& options);

}  // namespace oitbench
